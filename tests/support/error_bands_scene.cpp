// Error bands on a whole scene: which primitive a closest-hit query must find, or that rounding
// may decide it (docs/hard-cases.md §0). The per-kind bands are in error_bands.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "raylane/trace/brute_force.h"
#include "support/error_bands.h"
#include "support/interval.h"

namespace raylane::testing {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Every bound above amounts to moving the ray or the primitive by a few tens of u times the
// distance scale |o − centre| + extent (γ10 ≈ 2^-20.7 at most per term), in position or, for
// directions, in angle times distance. A line that passes 2^-12 of that scale away from the
// primitive's bounds is a clear miss by a factor of hundreds; the band test checks this
// shortcut against full classification on its own ray sets.
bool line_misses_grown_bounds(const Bounds3f& b, const Rayd& ray) {
  glm::dvec3 lo(b.lo), hi(b.hi);
  double g = 0x1p-12 * (length(ray.o - (lo + hi) * 0.5) + length(hi - lo));
  double t0 = -kInf, t1 = kInf;
  for (int k = 0; k < 3; ++k) {
    double l = lo[k] - g, h = hi[k] + g;
    if (ray.d[k] == 0) {
      if (ray.o[k] < l || ray.o[k] > h) return true;
      continue;
    }
    double a = (l - ray.o[k]) / ray.d[k], c = (h - ray.o[k]) / ray.d[k];
    t0 = std::max(t0, std::min(a, c));
    t1 = std::min(t1, std::max(a, c));
  }
  return t0 > t1;
}

// Which of two clear hits is nearer: the gap between the reference's t against the room their
// intervals leave (equal t, e.g. coplanar faces, is always in the band).
Criterion order_criterion(const PrimVerdict& nearer, const PrimVerdict& farther) {
  return {farther.t_ref - nearer.t_ref,
          gap(nearer.t_ref, nearer.t.hi) + gap(farther.t_ref, farther.t.lo)};
}

}  // namespace

PrimVerdict classify(const Scene& scene, PrimRef prim, const Rayd& ray) {
  return dispatch(prim.tag(), [&](auto kind) {
    return classify(scene.table<decltype(kind)>(), prim.row(), ray);
  });
}

// The kernel commits, in whatever order the traversal meets them, a hit that is nearer than
// the nearest so far (simd/packet.h). So the nearest clear hit wins for sure when every
// other primitive that might be hit has all its possible t beyond all of the winner's.
RayVerdict classify_closest(const Scene& scene, const Rayd& ray, bool skip_far_bounds) {
  RayVerdict out;
  if (!ray_is_valid(ray)) return out;
  struct Candidate {
    PrimRef prim;
    PrimVerdict v;
  };
  std::vector<Candidate> maybe;  // every primitive that is not a clear miss
  PrimKinds::for_each([&](auto kind) {
    const auto& table = scene.table<decltype(kind)>();
    for (uint32_t row = 0; row < table.size(); ++row) {
      if (skip_far_bounds && line_misses_grown_bounds(table.bounds(row), ray)) continue;
      PrimVerdict v = classify(table, row, ray);
      if (v.cls != RayClass::kClearMiss) maybe.push_back({PrimRef(tag_of<decltype(kind)>, row), v});
    }
  });
  if (maybe.empty()) return out;
  const Candidate* best = nullptr;
  for (const Candidate& c : maybe)
    if (c.v.cls == RayClass::kClearHit &&
        (!best || c.v.t_ref < best->v.t_ref || (c.v.t_ref == best->v.t_ref && c.prim < best->prim)))
      best = &c;
  bool ambiguous = false;
  out.band_ratio = kInf;
  for (const Candidate& c : maybe)
    if (&c != best && (!best || c.v.t.lo <= best->v.t.hi)) {
      ambiguous = true;
      out.band_ratio = std::min(out.band_ratio, c.v.cls == RayClass::kClearHit
                                                    ? order_criterion(best->v, c.v).ratio()
                                                    : c.v.decisive.ratio());
    }
  if (ambiguous) {
    out.cls = RayClass::kBand;
    return out;
  }
  out.cls = RayClass::kClearHit;
  out.band_ratio = 0;
  out.prim = best->prim;
  out.t = best->v.t_ref;
  out.t_bound = std::max(gap(out.t, best->v.t.lo), gap(out.t, best->v.t.hi));
  return out;
}

}  // namespace raylane::testing
