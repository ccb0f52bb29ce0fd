// The packet tracer: traces ray streams through the BVH in SIMD packets, with the kernels of
// the instruction set chosen at run time (SSE4.2, AVX2+FMA or AVX-512). Baseline code uses
// this; only the per-ISA translation units see xsimd.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

#include "raylane/bvh/bvh.h"
#include "raylane/scene/scene.h"
#include "raylane/simd/isa.h"
#include "raylane/trace/ray_stream.h"
#include "raylane/trace/traversal_counters.h"

namespace raylane {

// How rays go through the BVH. Packets of W consecutive rays over the binary tree pay when
// the rays are coherent (camera tiles, shadow rays from a tile to one light); one ray at a
// time over the 8-wide tree when they are not (bounces): there packets keep few lanes busy.
// Single rays need a BVH built with BvhConfig::wide_nodes; without it they go as packets.
enum class Traversal { kPackets, kSingleRays };

std::optional<Traversal> traversal_from_name(std::string_view name);  // packets, rays
std::string_view traversal_name(Traversal t);

class PacketTracer {
 public:
  // Contract: isa_supported(isa).
  explicit PacketTracer(Isa isa = best_isa(), Traversal traversal = Traversal::kPackets)
      : isa_(isa), traversal_(traversal) {}
  Isa isa() const { return isa_; }
  Traversal traversal() const { return traversal_; }
  int width() const { return isa_width(isa_); }

  // Closest hit of every ray: hits.t (+inf for a miss) and hits.prim. Rays with NaN or inf
  // components, a zero direction or tmin > tmax miss without traversal (hard-cases N1).
  // Parallel over chunks of the stream with OpenMP.
  void closest(const Scene& scene, const Bvh& bvh, const RayStream& rays, HitStream& hits) const;
  // Occlusion: hits.prim = 0 where something lies in (tmin, tmax), kInvalidBits elsewhere.
  void occluded(const Scene& scene, const Bvh& bvh, const RayStream& rays, HitStream& hits) const;
  // closest() or occluded() through the instrumented traversal: the same answers, plus what
  // the traversal did (for benchmarks; slower).
  TraversalCounters trace_counted(const Scene& scene, const Bvh& bvh, const RayStream& rays,
                                  HitStream& hits, bool any_hit) const;

 private:
  void trace(const Scene& scene, const Bvh& bvh, const RayStream& rays, HitStream& hits,
             bool any_hit, TraversalCounters* counters) const;
  Isa isa_;
  Traversal traversal_;
};

namespace detail {
// Defined in src/simd/isa_<name>.cpp, each compiled for its instruction set. Trace rays
// [begin, end) of the stream; count what the traversal does into `counters` unless null.
void trace_sse42(const Scene&, const Bvh&, const RayStream&, std::size_t, std::size_t, HitStream&,
                 bool any_hit, Traversal traversal, TraversalCounters* counters);
void trace_avx2(const Scene&, const Bvh&, const RayStream&, std::size_t, std::size_t, HitStream&,
                bool any_hit, Traversal traversal, TraversalCounters* counters);
void trace_avx512(const Scene&, const Bvh&, const RayStream&, std::size_t, std::size_t, HitStream&,
                  bool any_hit, Traversal traversal, TraversalCounters* counters);
}  // namespace detail

}  // namespace raylane
