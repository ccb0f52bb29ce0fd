// The tracer a renderer calls, behind one batch interface, with one of three backends
// (trace/trace_backend.h): the SIMD tracer (packet, the default), single rays through the BVH
// with the double kernels (bvh), or the brute-force oracle (scalar). All three see the same
// scene (its tables permuted by the BVH build), so their answers — including primitive ids —
// can be compared pixel for pixel. Every call runs on the calling thread: the renderer's tile
// loop owns the threads (core/parallel.h).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "raylane/bvh/bvh.h"
#include "raylane/core/enum_names.h"
#include "raylane/scene/scene.h"
#include "raylane/trace/hit.h"
#include "raylane/trace/trace_backend.h"

namespace raylane {

enum class TracerBackend { kPacket, kBvh, kScalar };  // kPacket: the SimdTracer

inline constexpr EnumNames<TracerBackend, 3> kTracerBackendNames{{"packet", "bvh", "scalar"}};
inline std::optional<TracerBackend> tracer_backend_from_name(std::string_view name) {
  return kTracerBackendNames.from_name(name);
}
inline std::string_view tracer_backend_name(TracerBackend backend) {
  return kTracerBackendNames.name(backend);
}

class Tracer {
 public:
  // Contract: isa_supported(isa) (only the packet backend reads it).
  Tracer(const Scene& scene, const Bvh& bvh, TracerBackend backend, Isa isa = best_isa());

  // The closest hit of every ray, with its surface (computed by the double reference from
  // the ray as traced). SIMD rays are traced in float: origins and directions are rounded
  // first, and the surface is computed for the rounded ray, so t and the point agree.
  void closest(const std::vector<Rayd>& rays, std::vector<Hit>& hits) const;
  // closest() for rays already in float columns (the render's wavefronts), with the caller's
  // scratch, and surfaces only for rays[0, with_surface): the rest (shadow rays, say) get prim
  // and t alone (their surface and facing are unspecified); complete() fills in one of them
  // later. The packet tracer reads the rays as they are, without a conversion pass; the
  // references trace each ray widened to double (exactly). `rays` may be scratch.rays.
  void closest(const RayStream& rays, std::vector<Hit>& hits, std::size_t with_surface,
               TraceScratch& scratch) const;
  // closest() for float rays as two columns, prim and t alone (HitStream), for a caller that
  // reads hits column by column and asks surfaces() for the ones it needs (the render's lane
  // rows): no 96-byte record per ray. The packet tracer's t is its own; the references' double
  // t is rounded to the nearest float (their records, from the overload above, keep it whole).
  void closest(const RayStream& rays, HitStream& hits, TraceScratch& scratch) const;
  // The surface and facing of a hit closest() gave prim and t alone, for the ray it traced.
  void complete(const Rayd& ray, Hit& hit) const;
  // A componentwise bound on the error of a hit's double point (hit.surface.p, for `ray`), what
  // a ray leaving it must clear (offset_ray_origin): hit_point_error's float roundoffs of
  // |o| + |t·d| and, on a triangle, triangle_vertex_bound (the float kernel's error in telling
  // the sides of a plane grows with the vertices: docs/hard-cases.md R2).
  glm::dvec3 hit_point_bound(const Rayd& ray, const Hit& hit) const;
  // The surfaces of hit ray[r] of `hits` (each a hit, not a miss, of a closest() on `rays`)
  // into row r of `out`, for r in [0, ray.size()), in float with an error bound
  // (SurfaceColumns): from the kind's float lanes where it has them (surface_float_lanes:
  // spheres, boxes, triangles and cylinders, the same steps as complete()'s in float, all in one
  // pass in row order), else complete()'s surface (in double lanes where the kind has them)
  // rounded. For the references that surface is the one at the float t (its rounding lies within
  // the bound: float_hit_point_bound).
  void surfaces(const RayStream& rays, const HitStream& hits, std::span<const uint32_t> ray,
                const SurfaceColumns& out, TraceScratch& scratch) const;
  // Whether something lies in each ray's interval (tmin, tmax): blocked[i] 1 or 0, a ray's
  // traversal ending at the first blocker. aims[i], when `aims` is not empty, is the primitive
  // ray i is aimed at (a shadow ray's light; invalid for none): it does not block the ray, and
  // the ray is blocked only by what lies before it (SimdTracer::occluded; the references say
  // whether the closest hit is something else). SIMD rays are traced rounded to float, as
  // closest() traces them. Contract: `aims` is empty or holds one entry per ray.
  void occluded(const std::vector<Rayd>& rays, const std::vector<PrimRef>& aims,
                std::vector<uint8_t>& blocked, TraceScratch& scratch) const;
  // occluded() for float rays, each aimed at rays.aim[i] (rays.aim empty: no aims).
  void occluded(const RayStream& rays, std::vector<uint8_t>& blocked, TraceScratch& scratch) const;

  const Scene& scene() const { return scene_; }
  TracerBackend backend() const { return backend_; }
  Isa isa() const { return isa_; }

 private:
  const Scene& scene_;
  TracerBackend backend_;
  Isa isa_;
  std::unique_ptr<const TraceBackend> impl_;
};

}  // namespace raylane
