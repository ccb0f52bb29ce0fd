// The packet tracer's kernels, compiled once per instruction set (simd_tracer_sse42.cpp,
// simd_tracer_avx2.cpp, simd_tracer_avx512.cpp, each from trace/simd_tracer_impl.h) into one
// table of entry points each; a SimdTracer takes its set's table when it is made (as
// bvh/build_lanes.h for the builder and render/render_lanes.h for the render). No xsimd here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "raylane/trace/simd_tracer.h"

namespace raylane::detail {

struct TracerLanes {
  // Rays [begin, end) of the stream; what the traversal does counted into `counters` unless
  // null.
  void (*trace)(const Scene& scene, const Bvh& bvh, const RayStream& rays, std::size_t begin,
                std::size_t end, HitStream& hits, bool any_hit, Traversal traversal,
                TraversalCounters* counters);
  // The surfaces of hits of one kind (SimdTracer::surfaces), into the hits ...
  void (*surfaces)(const Scene& scene, const RayStream& rays, PrimTag kind,
                   std::span<const uint32_t> rows, Hit* hits);
  // ... or into columns.
  void (*surface_columns)(const Scene& scene, const RayStream& rays, PrimTag kind,
                          std::span<const uint32_t> rows, const uint32_t* ray,
                          const HitStream& hits, const SurfaceColumns& out);
  // The float-lane kinds' surfaces into columns, in row order (SimdTracer::float_surfaces).
  std::size_t (*float_surface_columns)(const Scene& scene, const RayStream& rays,
                                       std::span<const uint32_t> ray, const HitStream& hits,
                                       const SurfaceColumns& out, uint32_t* rest);
};

extern const TracerLanes kTracerLanesSse42, kTracerLanesAvx2, kTracerLanesAvx512;

// The kernels for `isa`, which the CPU must support (isa_supported).
const TracerLanes& tracer_lanes(Isa isa);

}  // namespace raylane::detail
