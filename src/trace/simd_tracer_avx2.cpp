// The packet tracer compiled for one instruction set (flags set in CMakeLists.txt).
#include "trace/simd_tracer_impl.h"

static_assert(XSIMD_WITH_FMA3_AVX2,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::detail {

void trace_avx2(const Scene& scene, const Bvh& bvh, const RayStream& rays, std::size_t begin,
                std::size_t end, HitStream& hits, bool any_hit, Traversal traversal,
                TraversalCounters* counters) {
  trace_range<xsimd::fma3<xsimd::avx2>>(scene, bvh, rays, begin, end, hits, any_hit, traversal,
                                        counters);
}

void surfaces_avx2(const Scene& scene, const RayStream& rays, PrimTag kind,
                   std::span<const uint32_t> rows, Hit* hits) {
  surfaces_of_kind<xsimd::fma3<xsimd::avx2>>(scene, rays, kind, rows,
                                             HitSink<xsimd::fma3<xsimd::avx2>>{hits});
}

void surface_columns_avx2(const Scene& scene, const RayStream& rays, PrimTag kind,
                          std::span<const uint32_t> rows, const uint32_t* ray, const Hit* hits,
                          const SurfaceColumns& out) {
  surfaces_of_kind<xsimd::fma3<xsimd::avx2>>(scene, rays, kind, rows,
                                             ColumnSink<xsimd::fma3<xsimd::avx2>>{ray, hits, out});
}

}  // namespace raylane::detail
