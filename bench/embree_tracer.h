// Intel Embree 3 (Debian's libembree-dev) on the same scene and the same rays, as the
// baseline raylane is measured against. Triangles are Embree triangles; spheres are Embree's
// own round primitive (RTC_GEOMETRY_TYPE_SPHERE_POINT); boxes and cylinders, which Embree
// lacks, are user geometry whose callbacks run raylane's double reference kernels. Default
// scene flags and build quality (Embree's fast, non-robust mode).
#pragma once

#include <cstddef>

#include "bench_scenes.h"
#include "raylane/trace/ray_stream.h"

namespace raylane::bench {

class EmbreeScene;

bool embree_available();  // false when the benchmark was built without Embree

// Built once per bench scene and cached; nullptr without Embree.
const EmbreeScene* embree_scene(const BenchScene& scene);

// Builds a fresh Embree scene of `scene` and returns its build time (seconds, the
// rtcCommitScene call) and the bytes Embree's memory monitor saw allocated.
struct EmbreeBuild {
  double seconds = 0;
  std::size_t bytes = 0;
};
EmbreeBuild embree_build_once(const BenchScene& scene);

class EmbreeScene {
 public:
  // `width` 1: rtcIntersect1/rtcOccluded1 per ray; 16: rtcIntersect16/rtcOccluded16 on 16
  // consecutive rays. Parallel over OpenMP's current thread count.
  void trace(const RayStream& rays, bool occlusion, int width, HitStream& hits) const;
  struct Impl;
  Impl* impl = nullptr;
};

}  // namespace raylane::bench
