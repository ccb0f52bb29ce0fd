// The ray sets every tracer is timed on (docs/benchmarks.md, "Ray sets"): primary rays, one per
// pixel in 4×4-pixel tiles; shadow rays from each primary hit toward the scene's light (any hit);
// diffuse bounces, cosine-distributed about each primary hit's normal (incoherent). Fixed
// seeds, so every tracer and every run sees the identical rays.
#pragma once

#include <string>

#include "bench_scenes.h"
#include "raylane/trace/ray_stream.h"

namespace raylane::bench {

enum class RayKind { kPrimary, kShadow, kDiffuse };

struct RaySet {
  RayStream rays;
  bool occlusion = false;  // shadow rays: any hit suffices
};

const char* ray_kind_name(RayKind kind);  // "primary", "shadow", "diffuse"

// Cached per scene and kind.
const RaySet& bench_rays(const BenchScene& scene, RayKind kind);

}  // namespace raylane::bench
