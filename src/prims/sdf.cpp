// Signed-distance blocks: writing a block, its bounds, and the double reference marcher —
// sphere tracing (Hart 1996, "Sphere tracing", §2-3): from where the ray enters the block's
// bounds, step by the distance, which never crosses the surface, until it falls below the
// tolerance (sdf.h) or the ray leaves the bounds or the steps run out.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <mutex>

#include "raylane/prims/sdf.h"

namespace raylane {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

template <class Table>
void truncate(Table& t, std::size_t rows) {
  std::apply([&](auto&... c) { (c.resize(rows), ...); }, t.columns());
}

}  // namespace

// Leaf `leaf`'s exact distance at p, from its kind's float columns read in double.
double sdf_leaf_distance_ref(const SdfTable& s, uint32_t leaf, const glm::dvec3& p) {
  const uint32_t i = s.leaf_row[leaf];
  switch (s.leaf_kind[leaf]) {
    case kSdfSphere:
      return sdf_sphere(p, glm::dvec3(s.spheres.center(i)), double(s.spheres.r[i]));
    case kSdfBox: {
      glm::dvec3 lo(s.boxes.lo(i)), hi(s.boxes.hi(i));
      return sdf_box(p, (lo + hi) * 0.5, (hi - lo) * 0.5);
    }
    case kSdfCylinder: {
      const CylinderTable& c = s.cylinders;
      glm::dvec3 u(c.unit_axis(i));
      double hh = 0.5 * double(c.h[i]);
      return sdf_cylinder(p, glm::dvec3(c.base(i)) + u * hh, u, hh, double(c.r[i]));
    }
    default: {
      const TorusColumns& t = s.tori;
      glm::dvec3 c(t.cx[i], t.cy[i], t.cz[i]), u(t.ux[i], t.uy[i], t.uz[i]);
      return sdf_torus(p, c, u, double(t.R[i]), double(t.r[i]));
    }
  }
}

namespace {

// One thread's march counts, written by that thread alone (relaxed loads and stores: no locked
// instruction in the kernels) and read by sdf_march_counts. A thread's slot outlives it, so
// its counts stay in the sums.
struct alignas(64) MarchSlot {
  std::atomic<uint64_t> marches{0}, steps{0}, out_of_steps{0};
};
std::mutex slots_mutex;
std::vector<std::unique_ptr<MarchSlot>>& march_slots() {
  static std::vector<std::unique_ptr<MarchSlot>> slots;
  return slots;
}
MarchSlot& my_march_slot() {
  thread_local MarchSlot* mine = [] {
    std::lock_guard<std::mutex> lock(slots_mutex);
    march_slots().push_back(std::make_unique<MarchSlot>());
    return march_slots().back().get();
  }();
  return *mine;
}
void bump(std::atomic<uint64_t>& a, uint64_t v) {
  a.store(a.load(std::memory_order_relaxed) + v, std::memory_order_relaxed);
}

}  // namespace

void sdf_count_marches(const SdfMarchCounts& c) {
  MarchSlot& s = my_march_slot();
  bump(s.marches, c.marches), bump(s.steps, c.steps), bump(s.out_of_steps, c.out_of_steps);
}

SdfMarchCounts sdf_march_counts() {
  std::lock_guard<std::mutex> lock(slots_mutex);
  SdfMarchCounts sum;
  for (const auto& s : march_slots()) {
    sum.marches += s->marches.load(std::memory_order_relaxed);
    sum.steps += s->steps.load(std::memory_order_relaxed);
    sum.out_of_steps += s->out_of_steps.load(std::memory_order_relaxed);
  }
  return sum;
}

std::optional<ParamError> TorusColumns::append(std::span<const double, 8> p) {
  glm::dvec3 a{float(p[3]), float(p[4]), float(p[5])};
  double len = length(a);
  if (!(len > 0.0) || !std::isfinite(len)) return ParamError{3, "torus axis must be non-zero"};
  if (!(float(p[6]) > 0.0f)) return ParamError{6, "torus major radius R must be > 0"};
  if (!(float(p[7]) > 0.0f)) return ParamError{7, "torus tube radius r must be > 0"};
  if (!(float(p[7]) <= float(p[6])))
    return ParamError{7, "torus tube radius r must be at most the major radius R"};
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(float(std::abs(p[k]) + p[6] + p[7])))
      return ParamError{0, "torus reaches beyond float (the largest is about 3.4e38)"};
  glm::dvec3 u = a / len;
  cx.push_back(float(p[0])), cy.push_back(float(p[1])), cz.push_back(float(p[2]));
  ux.push_back(float(u.x)), uy.push_back(float(u.y)), uz.push_back(float(u.z));
  R.push_back(float(p[6])), r.push_back(float(p[7]));
  return std::nullopt;
}

// The tube's centre circle (radius R about the axis u) reaches R·sqrt(1 − u_k²) along axis k;
// the tube adds r. The stored u is unit only to float rounding, hence the max.
Bounds3f TorusColumns::bounds(uint32_t i) const {
  glm::dvec3 c(cx[i], cy[i], cz[i]), u(ux[i], uy[i], uz[i]), g;
  for (int k = 0; k < 3; ++k)
    g[k] = double(R[i]) * std::sqrt(std::max(0.0, 1 - u[k] * u[k])) + double(r[i]);
  return round_out(Bounds3d(c - g, c + g));
}

Bounds3f SdfTable::leaf_bounds(uint32_t leaf) const {
  const uint32_t i = leaf_row[leaf];
  switch (leaf_kind[leaf]) {
    case kSdfSphere:
      return spheres.bounds(i);
    case kSdfBox:
      return boxes.bounds(i);
    case kSdfCylinder:
      return cylinders.bounds(i);
    default:
      return tori.bounds(i);
  }
}

void SdfTable::begin_block() {
  open_leaf_ = leaves(), open_program_ = program.size();
  open_rows_[0] = spheres.size(), open_rows_[1] = boxes.size();
  open_rows_[2] = cylinders.size(), open_rows_[3] = tori.size();
}

void SdfTable::push_leaf(uint32_t kind, uint32_t row, uint32_t mat) {
  leaf_kind.push_back(kind), leaf_row.push_back(row), material.push_back(mat);
  leaf_block.push_back(uint32_t(blocks()));
  add_code(uint32_t(leaves() - 1 - open_leaf_));
}

std::optional<ParamError> SdfTable::add_torus(std::span<const double, 8> p, uint32_t mat) {
  if (auto err = tori.append(p)) return err;
  push_leaf(kSdfTorus, uint32_t(tori.size() - 1), mat);
  return std::nullopt;
}

void SdfTable::drop_block() {
  leaf_kind.resize(open_leaf_), leaf_row.resize(open_leaf_), material.resize(open_leaf_);
  leaf_block.resize(open_leaf_);
  program.resize(open_program_), program_k.resize(open_program_);
  truncate(spheres, open_rows_[0]), truncate(boxes, open_rows_[1]);
  truncate(cylinders, open_rows_[2]), truncate(tori, open_rows_[3]);
}

// The bounds by the spec's rule, on a stack as the program runs: A ∪ B the union of the
// bounds, A ∩ B their intersection, A − B those of A; a smooth operator's widened by its k,
// more than the at most k/4 its smooth minimum moves the surface.
bool SdfTable::end_block() {
  Bounds3f stack[kSdfMaxLeaves];
  int top = 0;
  for (std::size_t j = open_program_; j < program.size(); ++j) {
    const uint32_t code = program[j];
    if (code < kSdfMaxLeaves) {
      stack[top++] = leaf_bounds(uint32_t(open_leaf_ + code));
      continue;
    }
    Bounds3f b = stack[--top], a = stack[--top];
    if (code == kSdfUnion || code == kSdfSmoothUnion) {
      a.extend(b);
    } else if (code == kSdfIntersect || code == kSdfSmoothIntersect) {
      Bounds3f both;  // assigned, not constructed: the constructor would sort the corners
      both.lo = max(a.lo, b.lo), both.hi = min(a.hi, b.hi);
      a = both.empty() ? Bounds3f() : both;
    }
    if (sdf_is_smooth(code) && !a.empty()) {
      glm::dvec3 k(program_k[j]);
      a = round_out(Bounds3d(glm::dvec3(a.lo) - k, glm::dvec3(a.hi) + k));
    }
    stack[top++] = a;
  }
  if (top != 1 || stack[0].empty()) {
    drop_block();
    return false;
  }
  const Bounds3f& b = stack[0];
  leaf_begin.push_back(uint32_t(open_leaf_)), leaf_count.push_back(open_leaves());
  program_begin.push_back(uint32_t(open_program_));
  program_count.push_back(uint32_t(program.size() - open_program_));
  lox.push_back(b.lo.x), loy.push_back(b.lo.y), loz.push_back(b.lo.z);
  hix.push_back(b.hi.x), hiy.push_back(b.hi.y), hiz.push_back(b.hi.z);
  block.push_back(uint32_t(blocks() - 1));
  begin_block();
  return true;
}

double sdf_distance_ref(const SdfTable& s, uint32_t block, const glm::dvec3& p) {
  double stack[kSdfMaxLeaves];
  int top = 0;
  const uint32_t first = s.leaf_begin[block], begin = s.program_begin[block];
  for (uint32_t j = begin; j < begin + s.program_count[block]; ++j) {
    const uint32_t code = s.program[j];
    if (code < kSdfMaxLeaves) {
      stack[top++] = sdf_leaf_distance_ref(s, first + code, p);
      continue;
    }
    double b = stack[--top];
    stack[top - 1] = sdf_combine(code, stack[top - 1], b, double(s.program_k[j]));
  }
  return stack[0];
}

uint32_t sdf_nearest_leaf_ref(const SdfTable& s, uint32_t block, const glm::dvec3& p) {
  const uint32_t first = s.leaf_begin[block];
  uint32_t best = first;
  double best_d = kInf;
  for (uint32_t i = first; i < first + s.leaf_count[block]; ++i) {
    double d = std::abs(sdf_leaf_distance_ref(s, i, p));
    if (d < best_d) best_d = d, best = i;
  }
  return best;
}

// A ray that starts inside the bounds may start on the surface (a secondary ray, offset by the
// hit point's rounding error only): it must leave the band |distance| < tolerance before a hit
// counts, so it steps by the tolerance while inside it. A ray entering the bounds is armed at
// once: a box's faces are its bounds. Marching by |distance| finds the exit of a ray that starts
// inside the solid. NaN distances or directions end the march as misses.
Sdf::LeafHit Sdf::hit_ref(const SdfTable& s, uint32_t row, const Rayd& ray) {
  const Bounds3f b = s.bounds(row);
  double t0 = -kInf, t1 = kInf;
  for (int k = 0; k < 3; ++k) {
    double tn, tf;
    detail::box_slab(double(b.lo[k]), double(b.hi[k]), ray.o[k], ray.d[k], tn, tf);
    t0 = tn > t0 ? tn : t0;
    t1 = tf < t1 ? tf : t1;
  }
  bool armed = t0 > ray.tmin;
  t0 = std::max(t0, ray.tmin), t1 = std::min(t1, ray.tmax);
  const double len = length(ray.d);
  LeafHit hit;
  if (!(t0 <= t1) || !(ray.tmin <= ray.tmax) || !(len > 0) || !std::isfinite(len)) return hit;
  const double o = std::max({std::abs(ray.o.x), std::abs(ray.o.y), std::abs(ray.o.z)});
  const uint32_t blk = s.block[row];
  double t = t0;
  for (; hit.steps < uint32_t(kSdfMaxSteps); ++hit.steps) {
    const glm::dvec3 p = ray.o + ray.d * t;
    double d = std::abs(sdf_distance_ref(s, blk, p));
    const double tol = sdf_tolerance(t * len, o);
    if (d < tol && armed) {
      hit.t = t, hit.row = sdf_nearest_leaf_ref(s, blk, p);
      return hit;
    }
    armed = armed || !(d < tol);
    t += std::max(d, tol) / len;
    if (!(t <= t1)) return hit;
  }
  return hit;
}

// Quilez's tetrahedron ("normals for an SDF", iquilezles.org): four samples at p + h·k_i, k_i
// four alternate corners of the cube (±1, ±1, ±1); weighted by k_i they sum to 4h·∇f + O(h³).
// h is the hit tolerance there: far above the distance's rounding, and small against the
// features the march resolves at all. The march stops up to the tolerance off the surface, far
// more than a secondary ray's offset (core/ray_offset.h), so the point is moved onto the
// surface by Newton steps along the normal, d/|∇f| each (a smooth minimum's gradient is
// shorter than 1 in the blend); a few leave it within the distance's rounding.
Surface surface_ref(const SdfTable& s, uint32_t leaf, const Rayd& ray, double t) {
  const uint32_t blk = s.leaf_block[leaf];
  const glm::dvec3 p = ray.at(t);
  const double o = std::max({std::abs(ray.o.x), std::abs(ray.o.y), std::abs(ray.o.z)});
  const double h = sdf_tolerance(t * length(ray.d), o);
  const glm::dvec3 k[4] = {{1, -1, -1}, {-1, -1, 1}, {-1, 1, -1}, {1, 1, 1}};
  glm::dvec3 g(0);
  for (const glm::dvec3& ki : k)
    g += ki * sdf_distance_ref(s, blk, p + ki * h);
  double gl = length(g);
  glm::dvec3 n = gl > 0 && std::isfinite(gl) ? g / gl : -normalize(ray.d);
  const double slope = gl / (4 * h);  // |∇f|: the samples sum to 4h·∇f
  glm::dvec3 on = p;
  for (int i = 0; i < 4 && gl > 0 && std::isfinite(gl); ++i) {
    double d = sdf_distance_ref(s, blk, on);
    if (std::isfinite(d)) on -= n * (d / slope);
  }
  return {on, n, n};
}

}  // namespace raylane
