#include "raylane/trace/packet_tracer.h"

#include <algorithm>

namespace raylane {

std::optional<Traversal> traversal_from_name(std::string_view name) {
  if (name == "packets") return Traversal::kPackets;
  if (name == "rays") return Traversal::kSingleRays;
  return std::nullopt;
}

std::string_view traversal_name(Traversal t) {
  return t == Traversal::kPackets ? "packets" : "rays";
}

void PacketTracer::closest(const Scene& scene, const Bvh& bvh, const RayStream& rays,
                           HitStream& hits) const {
  trace(scene, bvh, rays, hits, false, nullptr);
}

void PacketTracer::occluded(const Scene& scene, const Bvh& bvh, const RayStream& rays,
                            HitStream& hits) const {
  trace(scene, bvh, rays, hits, true, nullptr);
}

TraversalCounters PacketTracer::trace_counted(const Scene& scene, const Bvh& bvh,
                                              const RayStream& rays, HitStream& hits,
                                              bool any_hit) const {
  TraversalCounters total;
  total.width = traversal_ == Traversal::kSingleRays && !bvh.wide.empty() ? kWideArity : width();
  trace(scene, bvh, rays, hits, any_hit, &total);
  return total;
}

void PacketTracer::trace(const Scene& scene, const Bvh& bvh, const RayStream& rays, HitStream& hits,
                         bool any_hit, TraversalCounters* counters) const {
  auto* fn = isa_ == Isa::kAvx512 ? detail::trace_avx512
             : isa_ == Isa::kAvx2 ? detail::trace_avx2
                                  : detail::trace_sse42;
  hits.resize(rays.size());
  const Traversal traversal = bvh.wide.empty() && !bvh.empty() ? Traversal::kPackets : traversal_;
  // Chunks of whole packets (a multiple of 16 rays) keep camera tiles together.
  constexpr std::ptrdiff_t kChunk = 256;
  const std::ptrdiff_t n = std::ptrdiff_t(rays.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t begin = 0; begin < n; begin += kChunk) {
    TraversalCounters local;
    fn(scene, bvh, rays, std::size_t(begin), std::size_t(std::min(n, begin + kChunk)), hits,
       any_hit, traversal, counters ? &local : nullptr);
    if (counters) {
#pragma omp critical(raylane_traversal_counters)
      counters->add(local);
    }
  }
}

}  // namespace raylane
