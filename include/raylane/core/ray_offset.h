// Where a secondary ray starts: off the surface by a bound on the hit point's own rounding
// error, not by a fixed epsilon, so nothing re-hits its own surface or leaks at any scale
// (docs/hard-cases.md §5).
#pragma once

#include <cmath>

#include "raylane/core/numbers.h"
#include "raylane/core/ray.h"

namespace raylane {

// offset_ray_origin written once over the number type N (core/numbers.h) and its 3-vector V3:
// the double reference (glm::dvec3), its float twin (glm::vec3) and the float lanes
// (simd::FloatVec3). The offset is the error bound's projection on the normal, dot(|ng|, error)
// in glm::dot's order (offset_along_normal; a vertex's two rays share it), and each component of
// p + offset is then stepped one unit in the last place further from p, so that rounding the
// sum cannot lose the offset (pbrt-v4 `OffsetRayOrigin`, Pharr, Jakob, Humphreys 4th ed.
// §6.8.6).
template <class N, class V3>
N offset_along_normal(const V3& error, const V3& ng) {
  using K = Num<N>;
  return K::abs(ng.x) * error.x + K::abs(ng.y) * error.y + K::abs(ng.z) * error.z;
}

// p moved `along` along ng, to the side `toward` points to, and stepped away from p.
template <class N, class V3>
[[gnu::always_inline]] inline V3 offset_origin_by(const V3& p, const N& along, const V3& ng,
                                                  const V3& toward) {
  using K = Num<N>;
  const auto away = ng.x * toward.x + ng.y * toward.y + ng.z * toward.z < N(0.0);
  // The step goes by the normal's side, not the offset's: where the bound is 0 (a box face at
  // 0), the origin still leaves the surface by one unit in the last place.
  auto one = [&](const N& pk, const N& nk) {
    const N out = nk * along, side = K::select(away, K::negate(nk), nk);
    return K::next_towards(pk + K::select(away, K::negate(out), out), side);
  };
  return V3{one(p.x, ng.x), one(p.y, ng.y), one(p.z, ng.z)};
}

// `error` bounds p's error such that its projection on the normal, dot(|ng|, error), bounds p's
// distance from the true surface: what the offset must clear. (For most kinds it bounds
// |p − exact p| per component; a sphere's reprojected point may slide along the sphere by more,
// which no offset along the normal needs to cover: sphere_point_bound.)
template <class N, class V3>
V3 offset_origin(const V3& p, const V3& error, const V3& ng, const V3& toward) {
  return offset_origin_by<N>(p, offset_along_normal<N>(error, ng), ng, toward);
}

// The origin of a ray leaving surface point p: moved along the geometric normal, to the
// side `toward` points to, by a bound on p's own rounding error (pbrt-v4 `OffsetRayOrigin`;
// Wächter and Binder, Ray Tracing Gems ch. 6), so the ray cannot re-hit the surface it starts
// on. `p_error` is a componentwise bound on |p − exact p|.
glm::dvec3 offset_ray_origin(const glm::dvec3& p, const glm::dvec3& p_error, const glm::dvec3& ng,
                             const glm::dvec3& toward);

// A componentwise bound on the error of a hit point o + t·d whose t came from a float
// kernel: a float t is within a few ulps, so allow 2^5 float roundoffs of |o| + |t·d|.
glm::dvec3 hit_point_error(const Rayd& ray, double t);

// A componentwise bound on the error of a float hit point p: the traced point o + t·d, t from a
// float kernel within a few ulps (2^5 float roundoffs of |o| + |t·d|, as hit_point_error), two
// roundoffs more for o + t·d evaluated in float, and p's own rounding to float (one roundoff of
// |p|). Each constant carries 2^-20 more, which covers this sum's own five float roundings (a
// relative 5·2^-24), so the bound computed in float is never below the exact one (pbrt-v4
// §6.8.1's running error bounds). The kinds whose float surfaces have tighter bounds say so in
// their headers (sphere_point_bound, box_point_bound).
template <class N, class V3>
V3 float_hit_point_bound(const V3& o, const V3& d, const N& t, const V3& p) {
  using K = Num<N>;
  const N along_ray(34 * 0x1p-24 * (1 + 0x1p-20)), own(0x1p-24 * (1 + 0x1p-20));
  auto one = [&](const N& ok, const N& dk, const N& pk) {
    return (K::abs(ok) + K::abs(dk * t)) * along_ray + K::abs(pk) * own;
  };
  return V3{one(o.x, d.x, p.x), one(o.y, d.y, p.y), one(o.z, d.z, p.z)};
}

// shadow_ray_tmax (core/ray_offset.h) over the number type: the light point p + dist·wi
// projected on the ray from o, in dot's order; an infinite distance stays infinite.
template <class N, class V3>
N shadow_tmax(const V3& o, const V3& p, const V3& wi, const N& dist) {
  const N along = (p.x - o.x) * wi.x + (p.y - o.y) * wi.y + (p.z - o.z) * wi.z;
  return Num<N>::select(dist == N(HUGE_VAL), dist, dist + along);
}

// Where a shadow ray from o toward a light point ends: at the point's distance along the ray.
// `wi` is the unit direction from the shading point p to the light point, `dist` their
// distance (o is p moved off its surface, so the ray passes the point within that move). The
// ray is traced as an occlusion query aimed at the light (Tracer::occluded): the light's own
// surface, wherever rounding puts it, does not block it, and the query looks for blockers
// before it. Infinite for an infinite distance (the environment).
// Inline: the render loop computes one per shadow ray, in a loop a call would slow down.
inline double shadow_ray_tmax(const glm::dvec3& o, const glm::dvec3& p, const glm::dvec3& wi,
                              double dist) {
  return shadow_tmax<double>(o, p, wi, dist);
}

}  // namespace raylane
