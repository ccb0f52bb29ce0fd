// The packet tracer compiled for one instruction set (flags set in CMakeLists.txt).
#include "trace/simd_tracer_impl.h"

static_assert(XSIMD_WITH_AVX512BW,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::detail {

void trace_avx512(const Scene& scene, const Bvh& bvh, const RayStream& rays, std::size_t begin,
                  std::size_t end, HitStream& hits, bool any_hit, Traversal traversal,
                  TraversalCounters* counters) {
  trace_range<xsimd::avx512bw>(scene, bvh, rays, begin, end, hits, any_hit, traversal, counters);
}

void surfaces_avx512(const Scene& scene, const RayStream& rays, PrimTag kind,
                     std::span<const uint32_t> rows, Hit* hits) {
  surfaces_of_kind<xsimd::avx512bw>(scene, rays, kind, rows, HitSink<xsimd::avx512bw>{hits});
}

void surface_columns_avx512(const Scene& scene, const RayStream& rays, PrimTag kind,
                            std::span<const uint32_t> rows, const uint32_t* ray, const Hit* hits,
                            const SurfaceColumns& out) {
  surfaces_of_kind<xsimd::avx512bw>(scene, rays, kind, rows,
                                    ColumnSink<xsimd::avx512bw>{ray, hits, out});
}

}  // namespace raylane::detail
