#include "raylane/trace/simd_tracer.h"

#include <cassert>

#include <string>

namespace raylane {

std::string_view traversal_name(Traversal t) {
  return t == Traversal::kPackets ? "packets" : "rays";
}

void SimdTracer::closest(const Scene& scene, const Bvh& bvh, const RayStream& rays,
                         HitStream& hits) const {
  hits.resize(rays.size());
  trace(scene, bvh, rays, 0, rays.size(), hits, false, nullptr);
}

void SimdTracer::occluded(const Scene& scene, const Bvh& bvh, const RayStream& rays,
                          HitStream& hits) const {
  hits.resize(rays.size());
  trace(scene, bvh, rays, 0, rays.size(), hits, true, nullptr);
}

void SimdTracer::trace_range(const Scene& scene, const Bvh& bvh, const RayStream& rays,
                             std::size_t begin, std::size_t end, HitStream& hits,
                             bool any_hit) const {
  trace(scene, bvh, rays, begin, end, hits, any_hit, nullptr);
}

TraversalCounters SimdTracer::trace_counted(const Scene& scene, const Bvh& bvh,
                                            const RayStream& rays, HitStream& hits,
                                            bool any_hit) const {
  TraversalCounters total;
  hits.resize(rays.size());
  trace(scene, bvh, rays, 0, rays.size(), hits, any_hit, &total);
  return total;
}

void SimdTracer::trace(const Scene& scene, const Bvh& bvh, const RayStream& rays, std::size_t begin,
                       std::size_t end, HitStream& hits, bool any_hit,
                       TraversalCounters* counters) const {
  assert(rays.end.empty() || rays.end.size() == rays.size());  // the contract in simd_tracer.h
  auto* fn = isa_ == Isa::kAvx512 ? detail::trace_avx512
             : isa_ == Isa::kAvx2 ? detail::trace_avx2
                                  : detail::trace_sse42;
  const Traversal traversal = bvh.wide.empty() && !bvh.empty() ? Traversal::kPackets : traversal_;
  fn(scene, bvh, rays, begin, end, hits, any_hit, traversal, counters);
}

void SimdTracer::surfaces(const Scene& scene, const RayStream& rays, PrimTag kind,
                          std::span<const uint32_t> rows, Hit* hits) const {
  auto* fn = isa_ == Isa::kAvx512 ? detail::surfaces_avx512
             : isa_ == Isa::kAvx2 ? detail::surfaces_avx2
                                  : detail::surfaces_sse42;
  fn(scene, rays, kind, rows, hits);
}

void SimdTracer::surfaces(const Scene& scene, const RayStream& rays, PrimTag kind,
                          std::span<const uint32_t> rows, const uint32_t* ray, const Hit* hits,
                          const SurfaceColumns& out) const {
  auto* fn = isa_ == Isa::kAvx512 ? detail::surface_columns_avx512
             : isa_ == Isa::kAvx2 ? detail::surface_columns_avx2
                                  : detail::surface_columns_sse42;
  fn(scene, rays, kind, rows, ray, hits, out);
}

}  // namespace raylane
