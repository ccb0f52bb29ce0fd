// Intel Embree 3 (Debian's libembree-dev) on the same scene and the same rays, as the
// baseline raylane is measured against. Triangles are Embree triangles; spheres are Embree's
// own round primitive (RTC_GEOMETRY_TYPE_SPHERE_POINT); boxes and cylinders, which Embree
// lacks, are user geometry whose callbacks run raylane's double reference kernels. Default
// build quality; scene flags either the default (Embree's fast, non-robust mode) or
// RTC_SCENE_FLAG_ROBUST, Embree's watertight mode — the honest comparison, since raylane's
// only mode is watertight (Woop, Benthin and Wald 2013).
#pragma once

#include <cstddef>

#include "bench_scenes.h"
#include "raylane/trace/ray_stream.h"

namespace raylane::bench {

class EmbreeScene;

bool embree_available();  // false when the benchmark was built without Embree

// Which scene flags Embree builds with.
enum class EmbreeMode { kDefault, kRobust };

// Built once per bench scene and mode, and cached; nullptr without Embree.
const EmbreeScene* embree_scene(const BenchScene& scene, EmbreeMode mode = EmbreeMode::kDefault);

// Builds a fresh Embree scene of `scene` and returns its build time (seconds, the
// rtcCommitScene call) and the bytes Embree's memory monitor saw allocated.
struct EmbreeBuild {
  double seconds = 0;
  std::size_t bytes = 0;
};
EmbreeBuild embree_build_once(const BenchScene& scene, EmbreeMode mode = EmbreeMode::kDefault);

class EmbreeScene {
 public:
  // `width` 1: rtcIntersect1/rtcOccluded1 per ray; 16: rtcIntersect16/rtcOccluded16 on 16
  // consecutive rays. Parallel over OpenMP's current thread count.
  void trace(const RayStream& rays, bool occlusion, int width, HitStream& hits) const;
  struct Impl;
  Impl* impl = nullptr;
};

}  // namespace raylane::bench
