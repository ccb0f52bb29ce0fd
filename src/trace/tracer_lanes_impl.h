// The table of tracer kernels (trace/tracer_lanes.h) for one instruction set A: the one source
// that simd_tracer_sse42.cpp, simd_tracer_avx2.cpp and simd_tracer_avx512.cpp each compile
// with their own flags. Include from those files only.
#pragma once

#include "trace/simd_tracer_impl.h"
#include "trace/tracer_lanes.h"

namespace raylane::detail {

template <class A>
void surfaces_into_hits(const Scene& scene, const RayStream& rays, PrimTag kind,
                        std::span<const uint32_t> rows, Hit* hits) {
  surfaces_of_kind<A>(scene, rays, kind, rows, HitSink<A>{hits});
}

template <class A>
void surfaces_into_columns(const Scene& scene, const RayStream& rays, PrimTag kind,
                           std::span<const uint32_t> rows, const uint32_t* ray,
                           const HitStream& hits, const SurfaceColumns& out) {
  surfaces_of_kind<A>(scene, rays, kind, rows,
                      ColumnSink<A>{ray, hits.t.data(), hits.prim.data(), out});
}

template <class A>
constexpr TracerLanes tracer_lanes_for() {
  return {trace_range<A>, surfaces_into_hits<A>, surfaces_into_columns<A>,
          float_surfaces_in_row_order<A>};
}

}  // namespace raylane::detail
