// Every tracer the benchmark times, behind one interface: a ray stream in, t and primitive
// out (HitStream; occlusion: prim 0 = occluded), so all of them run on identical rays and
// are checked against the same double-precision reference.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "bench_scenes.h"
#include "raylane/trace/ray_stream.h"
#include "raylane/trace/traversal_counters.h"

namespace raylane::bench {

struct BenchTracer {
  std::string name;
  // Traces every ray of the stream; parallel over OpenMP's current thread count.
  std::function<void(const RayStream&, bool occlusion, HitStream&)> trace;
  // raylane's packet tracers only: one instrumented trace, for the "where the time goes"
  // counters (nodes and primitives tested per ray, lane utilisation).
  std::function<TraversalCounters(const RayStream&, bool occlusion, HitStream&)> count;
};

// What `raylane render` traces with on this CPU ("raylane-render": the widest ISA's packets on
// the BVH render_bvh_config builds, so hybrid packets where that has 8-wide nodes), then
// raylane's packet tracer at each ISA this CPU has, on the BVH with 8-wide nodes, with hybrid
// packets ("raylane-avx2") and with
// single rays over the 8-wide tree ("raylane-avx2-rays"), raylane's scalar path (single rays
// through the BVH with the double reference kernels) and, when built with Embree, Embree's
// single-ray and 16-wide packet calls ("embree-1", "embree-16"), also on a scene built with
// RTC_SCENE_FLAG_ROBUST ("embree-robust-1", "embree-robust-16").
inline constexpr const char* kRenderTracerName = "raylane-render";
std::vector<std::string> bench_tracer_names();
BenchTracer bench_tracer(const BenchScene& scene, const std::string& name);

// Agreement with the double reference (closest_hit_bvh_ref / any_hit_bvh_ref on the float
// rays converted exactly to double), on every `stride`-th ray: a ray agrees when hit/miss
// matches and t is within a relative 1e-4 (docs/ray-sets.md; another primitive at the same
// t, e.g. across a shared edge, agrees).
struct Agreement {
  std::size_t checked = 0, disagree = 0;
  double rate() const { return checked ? double(disagree) / double(checked) : 0.0; }
};
Agreement check_against_reference(const BenchScene& scene, const RayStream& rays, bool occlusion,
                                  const HitStream& hits, std::size_t stride);

}  // namespace raylane::bench
