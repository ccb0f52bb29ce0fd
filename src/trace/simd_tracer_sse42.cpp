// The packet tracer (trace/tracer_lanes.h) compiled for one instruction set (flags set in
// CMakeLists.txt).
#include "trace/simd_tracer_impl.h"
#include "trace/tracer_lanes.h"

static_assert(XSIMD_WITH_SSE4_2,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::detail {

namespace {

using A = xsimd::sse4_2;

void surfaces_into_hits(const Scene& scene, const RayStream& rays, PrimTag kind,
                        std::span<const uint32_t> rows, Hit* hits) {
  surfaces_of_kind<A>(scene, rays, kind, rows, HitSink<A>{hits});
}

void surfaces_into_columns(const Scene& scene, const RayStream& rays, PrimTag kind,
                           std::span<const uint32_t> rows, const uint32_t* ray, const Hit* hits,
                           const SurfaceColumns& out) {
  surfaces_of_kind<A>(scene, rays, kind, rows, ColumnSink<A>{ray, hits, out});
}

}  // namespace

const TracerLanes kTracerLanesSse42 = {trace_range<A>, surfaces_into_hits, surfaces_into_columns};

}  // namespace raylane::detail
