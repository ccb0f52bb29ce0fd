// The SIMD tracer: traces ray streams through the BVH with the kernels of the instruction set
// chosen at run time (SSE4.2, AVX2+FMA or AVX-512), as packets of W rays over the binary tree
// or one ray at a time over the 8-wide tree. Baseline code uses this header; only the per-ISA
// translation units (src/trace/simd_tracer_<isa>.cpp) see xsimd.
//
// Threads: every call traces on the calling thread. The outermost loop owns the threads
// (docs/design.md, "Threads"): a renderer's tile loop, or a caller that splits a stream with
// parallel_chunks (core/parallel.h) and hands each chunk to trace_range.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

#include "raylane/bvh/bvh.h"
#include "raylane/scene/scene.h"
#include "raylane/simd/isa.h"
#include "raylane/trace/hit.h"
#include "raylane/trace/ray_stream.h"
#include "raylane/trace/surface_columns.h"
#include "raylane/trace/traversal_counters.h"

namespace raylane {

// How rays go through the BVH: packets of W consecutive rays over the binary tree (the
// default: they win on every benchmark set), or one ray at a time over the 8-wide tree (kept
// as a benchmark tracer: bench/README.md). Single rays need a BVH built with
// BvhConfig::wide_nodes; without it they go as packets.
enum class Traversal { kPackets, kSingleRays };

std::string_view traversal_name(Traversal t);  // "packets", "rays"

// Rays per chunk when a caller splits a stream over its threads: a multiple of every packet
// width (4, 8, 16), so the packets are the ones one serial pass would make.
inline constexpr std::size_t kTraceChunk = 256;

namespace detail {
struct TracerLanes;
}  // namespace detail

class SimdTracer {
 public:
  // Contract: isa_supported(isa).
  explicit SimdTracer(Isa isa = best_isa(), Traversal traversal = Traversal::kPackets);
  Isa isa() const { return isa_; }
  Traversal traversal() const { return traversal_; }
  int width() const { return isa_width(isa_); }  // rays per packet

  // Closest hit of every ray: hits.t (+inf for a miss) and hits.prim. Rays with NaN or inf
  // components, a zero direction or tmin > tmax miss without traversal (docs/hard-cases.md N1).
  void closest(const Scene& scene, const Bvh& bvh, const RayStream& rays, HitStream& hits) const;
  // Occlusion: hits.prim = 0 where something lies in (tmin, tmax), kInvalidBits elsewhere.
  // A ray aimed at a primitive (rays.aim) is blocked by anything else before that primitive's
  // hit, within (tmin, tmax); the primitive itself does not block it. (Something beyond the
  // aim's hit may still block it if found first: keep tmax at the aimed-at point.) rays.aim is
  // empty or one entry per ray (a contract: the caller's to keep, asserted in debug builds);
  // closest hit ignores it.
  void occluded(const Scene& scene, const Bvh& bvh, const RayStream& rays, HitStream& hits) const;
  // Rays [begin, end) of the stream into the same entries of `hits`, which must already hold
  // rays.size() entries: one chunk of a stream that the caller splits over its threads.
  void trace_range(const Scene& scene, const Bvh& bvh, const RayStream& rays, std::size_t begin,
                   std::size_t end, HitStream& hits, bool any_hit) const;
  // closest() or occluded() through the instrumented traversal: the same answers, plus what
  // the traversal did (for benchmarks; slower).
  TraversalCounters trace_counted(const Scene& scene, const Bvh& bvh, const RayStream& rays,
                                  HitStream& hits, bool any_hit) const;
  // The surfaces of hits[i] for each i in `rows`, all on primitives of one kind whose
  // surface_in_lanes is true, in double lanes: h.surface and h.front_face exactly as
  // surface_ref gives them for the stream's ray i (the ray as traced) and h.t.
  void surfaces(const Scene& scene, const RayStream& rays, PrimTag kind,
                std::span<const uint32_t> rows, Hit* hits) const;
  // The surfaces written as columns: for each r in `rows`, hits[ray[r]]'s (traced as the
  // stream's ray ray[r]) into row r of `out`, the double lanes' rounded, with the float
  // point's bound (Tracer::surfaces), for a kind whose surface_in_float_lanes is false.
  void surfaces(const Scene& scene, const RayStream& rays, PrimTag kind,
                std::span<const uint32_t> rows, const uint32_t* ray, const HitStream& hits,
                const SurfaceColumns& out) const;
  // For every row r of `ray` whose hit's kind has surface_in_float_lanes, its surface in float
  // lanes with the kind's bound, as above, all such kinds in one pass in row order. The other
  // rows (of ray's size at most) are listed in `rest`, in order, for the call above; their
  // columns are left for it to write. Returns how many.
  std::size_t float_surfaces(const Scene& scene, const RayStream& rays,
                             std::span<const uint32_t> ray, const HitStream& hits,
                             const SurfaceColumns& out, uint32_t* rest) const;

 private:
  void trace(const Scene& scene, const Bvh& bvh, const RayStream& rays, std::size_t begin,
             std::size_t end, HitStream& hits, bool any_hit, TraversalCounters* counters) const;
  Isa isa_;
  const detail::TracerLanes* lanes_;  // isa_'s kernels (src/trace/tracer_lanes.h)
  Traversal traversal_;
};

}  // namespace raylane
