#include "raylane/trace/bvh_ref.h"

#include <cmath>

#include "raylane/prims/prim_list.h"
#include "raylane/trace/brute_force.h"

namespace raylane {

namespace {

glm::dvec3 inverse(const glm::dvec3& d) {
  return {1.0 / d.x, 1.0 / d.y, 1.0 / d.z};
}

// Tests the rows of one leaf; `on_hit(ref, t)` returns true to stop early.
template <class OnHit>
bool visit_leaf(const Scene& scene, const Bvh& bvh, const BvhNode& leaf, const Rayd& ray,
                OnHit&& on_hit) {
  bool stop = false;
  for_each_run(bvh, leaf, [&](PrimRef head, uint32_t rows) {
    for (uint32_t i = 0; i < rows && !stop; ++i) {
      RowHit h = dispatch(head.tag(), [&](auto kind) {
        return hit_ref<decltype(kind)>(scene.table<decltype(kind)>(), head.row() + i, ray);
      });
      stop = h.t < ray.tmax && on_hit(PrimRef(head.tag(), h.row), h.t);
    }
  });
  return stop;
}

// Depth-first traversal; `on_hit` may shrink `ray.tmax`; returns true if stopped early.
template <class OnHit>
bool traverse(const Scene& scene, const Bvh& bvh, Rayd& ray, OnHit&& on_hit) {
  if (bvh.empty() || !ray_is_valid(ray)) return false;
  glm::dvec3 inv_d = inverse(ray.d);
  uint32_t stack[kBvhStackSize];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& n = bvh.nodes[stack[--top]];
    if (!ray_overlaps_box_ref(ray, inv_d, n.bounds(), ray.tmax)) continue;
    if (n.is_leaf()) {
      if (visit_leaf(scene, bvh, n, ray, on_hit)) return true;
      continue;
    }
    // Visit the near child first: push the far one first.
    bool left_first = !std::signbit(ray.d[n.axis]);
    stack[top++] = left_first ? n.index + 1 : n.index;
    stack[top++] = left_first ? n.index : n.index + 1;
  }
  return false;
}

}  // namespace

bool ray_overlaps_box_ref(const Rayd& ray, const glm::dvec3& inv_d, const Bounds3f& box,
                          double tmax) {
  double t0 = ray.tmin, t1 = tmax;
  for (int k = 0; k < 3; ++k) {
    // The near plane follows the sign bit of d, so +0 and −0 agree (docs/hard-cases.md B3).
    bool neg = std::signbit(ray.d[k]);
    double near_plane = neg ? box.hi[k] : box.lo[k];
    double far_plane = neg ? box.lo[k] : box.hi[k];
    double tn = (near_plane - ray.o[k]) * inv_d[k];
    double tf = (far_plane - ray.o[k]) * inv_d[k];
    // 0·inf = NaN when the origin lies in a slab plane of a parallel ray: the comparisons
    // below then keep the accumulator, which is the closed-box answer (docs/hard-cases.md B4).
    // Each t carries three roundings in double (difference, reciprocal, product): widen the
    // interval by a relative 4u on both ends, so rounding never closes it (Ize 2013).
    tn -= std::abs(tn) * (4 * 0x1p-53);
    tf += std::abs(tf) * (4 * 0x1p-53);
    t0 = tn > t0 ? tn : t0;
    t1 = tf < t1 ? tf : t1;
  }
  return t0 <= t1;
}

Hit closest_hit_bvh_ref(const Scene& scene, const Bvh& bvh, const Rayd& ray) {
  Rayd r = ray;
  Hit best;
  traverse(scene, bvh, r, [&](PrimRef ref, double t) {
    // Equal t: the lower ref wins, as in the brute-force oracle.
    if (t < best.t || (t == best.t && ref < best.prim)) {
      best.t = t;
      best.prim = ref;
      r.tmax = std::nextafter(t, INFINITY);  // keep equal-t candidates in range for the tie-break
    }
    return false;
  });
  if (best.hit()) {
    best.surface = dispatch(best.prim.tag(), [&](auto kind) {
      return surface_ref(scene.table<decltype(kind)>(), best.prim.row(), ray, best.t);
    });
    best.front_face = dot(ray.d, best.surface.ng) < 0;
  }
  return best;
}

bool any_hit_bvh_ref(const Scene& scene, const Bvh& bvh, const Rayd& ray) {
  Rayd r = ray;
  return traverse(scene, bvh, r, [](PrimRef, double) { return true; });
}

}  // namespace raylane
