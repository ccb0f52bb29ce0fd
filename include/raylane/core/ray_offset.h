// Where a secondary ray starts: off the surface by a bound on the hit point's own rounding
// error, not by a fixed epsilon, so nothing re-hits its own surface or leaks at any scale
// (docs/hard-cases.md §5).
#pragma once

#include <cmath>

#include "raylane/core/ray.h"

namespace raylane {

// The origin of a ray leaving surface point p: moved along the geometric normal, to the
// side `toward` points to, by a bound on p's own rounding error (pbrt-v4 `OffsetRayOrigin`;
// Wächter and Binder, Ray Tracing Gems ch. 6), so the ray cannot re-hit the surface it starts
// on. `p_error` is a componentwise bound on |p − exact p|.
glm::dvec3 offset_ray_origin(const glm::dvec3& p, const glm::dvec3& p_error, const glm::dvec3& ng,
                             const glm::dvec3& toward);

// A componentwise bound on the error of a hit point o + t·d whose t came from a float
// kernel: a float t is within a few ulps, so allow 2^5 float roundoffs of |o| + |t·d|.
glm::dvec3 hit_point_error(const Rayd& ray, double t);

// Where a shadow ray from o toward a light point ends: at the point's distance along the ray.
// `wi` is the unit direction from the shading point p to the light point, `dist` their
// distance (o is p moved off its surface, so the ray passes the point within that move). The
// ray is traced as an occlusion query aimed at the light (Tracer::occluded): the light's own
// surface, wherever rounding puts it, does not block it, and the query looks for blockers
// before it. Infinite for an infinite distance (the environment).
// Inline: the render loop computes one per shadow ray, in a loop a call would slow down.
inline double shadow_ray_tmax(const glm::dvec3& o, const glm::dvec3& p, const glm::dvec3& wi,
                              double dist) {
  if (std::isinf(dist)) return dist;  // the environment: nothing may lie anywhere on the ray
  return dist + dot(p - o, wi);       // the light point p + dist·wi, projected on the ray
}

}  // namespace raylane
