// Single-ray BVH traversal with the double-precision reference kernels: the BVH's own oracle
// (BVH + reference kernels must equal brute force exactly) and the `--tracer bvh` path.
#pragma once

#include "raylane/bvh/bvh.h"
#include "raylane/scene/scene.h"
#include "raylane/trace/hit.h"

namespace raylane {

Hit closest_hit_bvh_ref(const Scene& scene, const Bvh& bvh, const Rayd& ray);
bool any_hit_bvh_ref(const Scene& scene, const Bvh& bvh, const Rayd& ray);

// The slab test of a float node box against a double ray: does the ray's segment
// (tmin, tmax) overlap the box? Closed box; NaN-safe; ±0 direction components give the same
// answer (docs/hard-cases.md B3, B4). Exposed for tests.
bool ray_overlaps_box_ref(const Rayd& ray, const glm::dvec3& inv_d, const Bounds3f& box,
                          double tmax);

}  // namespace raylane
