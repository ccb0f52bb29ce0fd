// CSG blocks: appending a block, and the double reference kernel — Roth's ray classification
// (Roth 1982, "Ray casting for modeling solids", CGIP 18(2), §3-4): each convex leaf meets the
// ray's line in one interval, and the solid's boundary along the ray lies where the program's
// classification of the points just before and just after a leaf's entry or exit differs.
#include <algorithm>
#include <limits>

#include "raylane/prims/csg.h"

namespace raylane {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Copies row i of `src` onto the end of `dst`, column by column.
template <class Table>
void copy_row(Table& dst, Table& src, uint32_t i) {
  auto d = dst.columns();
  auto s = src.columns();
  [&]<std::size_t... k>(std::index_sequence<k...>) {
    (std::get<k>(d).push_back(std::get<k>(s)[i]), ...);
  }
  (std::make_index_sequence<std::tuple_size_v<decltype(d)>>{});
}

// The sphere's interval: the sphere reference's discriminant and roots (sphere.h).
bool sphere_interval(const SphereTable& s, uint32_t i, const Rayd& ray, double& t0, double& t1) {
  glm::dvec3 f = ray.o - glm::dvec3(s.center(i));
  double r = s.r[i];
  double a = dot(ray.d, ray.d), b = dot(f, ray.d);
  glm::dvec3 l = f - (b / a) * ray.d;
  double disc = r * r - dot(l, l);
  if (!(disc >= 0)) return false;
  solve_quadratic(a, b, dot(f, f) - r * r, a * disc, t0, t1);
  return true;
}

// The box's interval: the slab method with NaN-keeping extrema, as the box reference (box.h).
bool box_interval(const BoxTable& b, uint32_t i, const Rayd& ray, double& t0, double& t1) {
  glm::dvec3 lo(b.lo(i)), hi(b.hi(i));
  t0 = -kInf, t1 = kInf;
  for (int k = 0; k < 3; ++k) {
    double tn, tf;
    detail::box_slab(lo[k], hi[k], ray.o[k], ray.d[k], tn, tf);
    t0 = tn > t0 ? tn : t0;
    t1 = tf < t1 ? tf : t1;
  }
  return t0 <= t1;
}

}  // namespace

void csg_leaf_interval_ref(const CsgTable& c, uint32_t leaf, const Rayd& ray, double& t0,
                           double& t1) {
  uint32_t row = c.leaf_row[leaf];
  bool hit = c.leaf_kind[leaf] == kCsgSphere ? sphere_interval(c.spheres, row, ray, t0, t1)
             : c.leaf_kind[leaf] == kCsgBox
                 ? box_interval(c.boxes, row, ray, t0, t1)
                 : detail::cylinder_interval(c.cylinders, row, ray, t0, t1);
  if (!hit) t0 = t1 = kInf;
}

namespace {

// Which leaves hold the points just before (after) t: the closed intervals, entered at t0 and
// left at t1.
uint64_t inside_before(const double* t0, const double* t1, uint32_t n, double t) {
  uint64_t m = 0;
  for (uint32_t i = 0; i < n; ++i)
    m |= uint64_t(t0[i] < t && t <= t1[i]) << i;
  return m;
}
uint64_t inside_after(const double* t0, const double* t1, uint32_t n, double t) {
  uint64_t m = 0;
  for (uint32_t i = 0; i < n; ++i)
    m |= uint64_t(t0[i] <= t && t < t1[i]) << i;
  return m;
}

// The leaf seen at a boundary t: the first (in block order) whose own crossing alone changes the
// classification; if only crossings together do (coincident faces of an intersection), the first
// leaf with an end at t. "Where two leaves' surfaces coincide exactly, the earlier leaf in the
// block is the one seen."
uint32_t leaf_at(std::span<const uint32_t> program, const double* t0, const double* t1, uint32_t n,
                 double t, uint64_t before, uint64_t after) {
  bool f = csg_classify(program, before);
  uint32_t first = n;
  for (uint32_t i = 0; i < n; ++i) {
    if (t0[i] != t && t1[i] != t) continue;
    first = std::min(first, i);
    uint64_t bit = uint64_t(1) << i;
    if (csg_classify(program, (before & ~bit) | (after & bit)) != f) return i;
  }
  return first;
}

}  // namespace

Bounds3f CsgTable::leaf_bounds(uint32_t leaf) const {
  uint32_t row = leaf_row[leaf];
  switch (leaf_kind[leaf]) {
    case kCsgSphere:
      return spheres.bounds(row);
    case kCsgBox:
      return boxes.bounds(row);
    default:
      return cylinders.bounds(row);
  }
}

bool CsgTable::append_block(CsgTable& draft) {
  const auto first = uint32_t(leaf_kind.size());
  const auto n = uint32_t(draft.leaves());
  Bounds3f b = csg_bounds(draft.program, [&](uint32_t i) { return draft.leaf_bounds(i); });
  if (b.empty()) return false;
  uint8_t flips[kCsgMaxLeaves] = {};
  csg_flips(draft.program, std::span<uint8_t>(flips, n));
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t row = draft.leaf_row[i];
    std::size_t kind_rows = draft.leaf_kind[i] == kCsgSphere ? spheres.size()
                            : draft.leaf_kind[i] == kCsgBox  ? boxes.size()
                                                             : cylinders.size();
    if (draft.leaf_kind[i] == kCsgSphere) copy_row(spheres, draft.spheres, row);
    if (draft.leaf_kind[i] == kCsgBox) copy_row(boxes, draft.boxes, row);
    if (draft.leaf_kind[i] == kCsgCylinder) copy_row(cylinders, draft.cylinders, row);
    leaf_kind.push_back(draft.leaf_kind[i]);
    leaf_row.push_back(uint32_t(kind_rows));
    material.push_back(draft.material[i]);
    leaf_flip.push_back(flips[i]);
  }
  leaf_begin.push_back(first);
  leaf_count.push_back(n);
  program_begin.push_back(uint32_t(program.size()));
  program_count.push_back(uint32_t(draft.program.size()));
  program.insert(program.end(), draft.program.begin(), draft.program.end());
  lox.push_back(b.lo.x), loy.push_back(b.lo.y), loz.push_back(b.lo.z);
  hix.push_back(b.hi.x), hiy.push_back(b.hi.y), hiz.push_back(b.hi.z);
  return true;
}

// The events are the leaves' ends inside (tmin, tmax), sorted; the first at which the
// classification before and after differ is the hit. At most 2 × 64 events, on the stack.
Csg::LeafHit Csg::hit_ref(const CsgTable& c, uint32_t block, const Rayd& ray) {
  const uint32_t n = c.leaf_count[block], first = c.leaf_begin[block];
  const std::span<const uint32_t> program = c.program_of(block);
  double t0[kCsgMaxLeaves], t1[kCsgMaxLeaves], events[2 * kCsgMaxLeaves];
  uint32_t m = 0;
  for (uint32_t i = 0; i < n; ++i) {
    csg_leaf_interval_ref(c, first + i, ray, t0[i], t1[i]);
    for (double e : {t0[i], t1[i]})
      if (e > ray.tmin && e < ray.tmax) events[m++] = e;
  }
  std::sort(events, events + m);
  for (uint32_t k = 0; k < m; ++k) {
    double t = events[k];
    if (k > 0 && t == events[k - 1]) continue;
    uint64_t before = inside_before(t0, t1, n, t), after = inside_after(t0, t1, n, t);
    if (csg_classify(program, before) != csg_classify(program, after))
      return {t, first + leaf_at(program, t0, t1, n, t, before, after)};
  }
  return {};
}

Surface surface_ref(const CsgTable& c, uint32_t leaf, const Rayd& ray, double t) {
  uint32_t row = c.leaf_row[leaf];
  Surface s = c.leaf_kind[leaf] == kCsgSphere ? surface_ref(c.spheres, row, ray, t)
              : c.leaf_kind[leaf] == kCsgBox  ? surface_ref(c.boxes, row, ray, t)
                                              : surface_ref(c.cylinders, row, ray, t);
  if (c.leaf_flip[leaf]) s.ng = -s.ng, s.ns = -s.ns;
  return s;
}

TexCoord texcoord_ref(const CsgTable& c, uint32_t leaf, const Surface& s) {
  uint32_t row = c.leaf_row[leaf];
  switch (c.leaf_kind[leaf]) {
    case kCsgSphere:
      return texcoord_ref(c.spheres, row, s);
    case kCsgBox:
      return texcoord_ref(c.boxes, row, s);
    default:
      return texcoord_ref(c.cylinders, row, s);
  }
}

}  // namespace raylane
