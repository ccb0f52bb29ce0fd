#include "raylane/trace/simd_tracer.h"

#include <cassert>

#include "trace/tracer_lanes.h"

#include <string>

namespace raylane {

std::string_view traversal_name(Traversal t) {
  return t == Traversal::kPackets ? "packets" : "rays";
}

SimdTracer::SimdTracer(Isa isa, Traversal traversal)
    : isa_(isa), lanes_(&detail::tracer_lanes(isa)), traversal_(traversal) {}

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
  assert(rays.aim.empty() || rays.aim.size() == rays.size());  // the contract in simd_tracer.h
  const Traversal traversal = bvh.wide.empty() && !bvh.empty() ? Traversal::kPackets : traversal_;
  lanes_->trace(scene, bvh, rays, begin, end, hits, any_hit, traversal, counters);
}

void SimdTracer::surfaces(const Scene& scene, const RayStream& rays, PrimTag kind,
                          std::span<const uint32_t> rows, Hit* hits) const {
  lanes_->surfaces(scene, rays, kind, rows, hits);
}

void SimdTracer::surfaces(const Scene& scene, const RayStream& rays, PrimTag kind,
                          std::span<const uint32_t> rows, const uint32_t* ray,
                          const HitStream& hits, const SurfaceColumns& out) const {
  lanes_->surface_columns(scene, rays, kind, rows, ray, hits, out);
}

std::size_t SimdTracer::float_surfaces(const Scene& scene, const RayStream& rays,
                                       std::span<const uint32_t> ray, const HitStream& hits,
                                       const SurfaceColumns& out, uint32_t* rest) const {
  return lanes_->float_surface_columns(scene, rays, ray, hits, out, rest);
}

namespace detail {

const TracerLanes& tracer_lanes(Isa isa) {
  return for_isa(isa, kTracerLanesSse42, kTracerLanesAvx2, kTracerLanesAvx512);
}

}  // namespace detail

}  // namespace raylane
