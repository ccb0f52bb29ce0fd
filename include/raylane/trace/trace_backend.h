// The ways a Tracer (trace/tracer.h) traces, one class each behind one small interface: the
// packet backend (the SIMD tracer, rays rounded to float, src/trace/packet_backend.cpp) and two
// references that trace each double ray on its own, through the BVH (trace/bvh_ref.h) or
// against every primitive (trace/brute_force.h) (src/trace/reference_backends.cpp). Tracer
// picks one by its TracerBackend name and forwards to it; nothing else needs this header.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "raylane/bvh/bvh.h"
#include "raylane/core/ray.h"
#include "raylane/prims/prim_list.h"
#include "raylane/scene/scene.h"
#include "raylane/simd/isa.h"
#include "raylane/trace/hit.h"
#include "raylane/trace/ray_stream.h"
#include "raylane/trace/surface_columns.h"

namespace raylane {

// Buffers a caller keeps between batches so that tracing allocates nothing once they have
// grown (one per thread: the render loop keeps one per wavefront).
struct TraceScratch {
  RayStream rays;
  HitStream hits;
  std::array<std::vector<uint32_t>, kPrimKindCount> by_kind;  // hits awaiting their surface
  std::vector<uint32_t> rest;  // rows the float surfaces' pass left (SimdTracer::float_surfaces)
};

// Each call is Tracer's of the same name (trace/tracer.h says what it answers).
class TraceBackend {
 public:
  virtual ~TraceBackend() = default;
  // Rays given in double: the references trace them as they are, the packet tracer rounded.
  virtual void closest(const std::vector<Rayd>& rays, std::vector<Hit>& hits,
                       TraceScratch& scratch) const = 0;
  virtual void occluded(const std::vector<Rayd>& rays, const std::vector<PrimRef>& aims,
                        std::vector<uint8_t>& blocked, TraceScratch& scratch) const = 0;
  // Rays given in float columns (the render's wavefronts): the references widen each exactly.
  virtual void closest(const RayStream& rays, std::vector<Hit>& hits, std::size_t with_surface,
                       TraceScratch& scratch) const = 0;
  virtual void closest(const RayStream& rays, HitStream& hits, TraceScratch& scratch) const = 0;
  virtual void occluded(const RayStream& rays, std::vector<uint8_t>& blocked,
                        TraceScratch& scratch) const = 0;
  virtual void surfaces(const RayStream& rays, const HitStream& hits, std::span<const uint32_t> ray,
                        const SurfaceColumns& out, TraceScratch& scratch) const = 0;
};

// Contract for the packet backend: isa_supported(isa).
std::unique_ptr<const TraceBackend> packet_backend(const Scene& scene, const Bvh& bvh, Isa isa);
std::unique_ptr<const TraceBackend> bvh_reference_backend(const Scene& scene, const Bvh& bvh);
std::unique_ptr<const TraceBackend> brute_force_backend(const Scene& scene);

// The surface of a hit on `prim` at t along `ray`, by its kind's double reference (surface_ref).
Surface surface_of(const Scene& scene, PrimRef prim, const Rayd& ray, double t);

// One surface into row r of `out`, from a Surface record of a hit on `prim`, for the ray that
// met it at t (the point's bound: float_hit_point_bound, core/ray_offset.h, and for a triangle
// triangle_vertex_bound too).
void store_surface(const SurfaceColumns& out, std::size_t r, const Scene& scene, PrimRef prim,
                   const Surface& s, const Rayd& ray, double t);

}  // namespace raylane
