// The brute-force oracle: every row of every table, with the double-precision reference
// kernels. Slow and simple on purpose; the BVH and the packet tracer are tested against it.
#pragma once

#include "raylane/core/ray.h"
#include "raylane/scene/scene.h"
#include "raylane/trace/hit.h"

namespace raylane {

// The nearest hit in (tmin, tmax); equal t goes to the lower PrimRef bits. Rays with NaN or
// inf components, a zero direction or tmin > tmax hit nothing (docs/hard-cases.md N1).
Hit closest_hit_ref(const Scene& scene, const Rayd& ray);
// Whether any surface lies in (tmin, tmax).
bool any_hit_ref(const Scene& scene, const Rayd& ray);

bool ray_is_valid(const Rayd& ray);

}  // namespace raylane
