#include "raylane/trace/tracer.h"

#include "raylane/core/ray_offset.h"
#include "raylane/prims/prim_list.h"

namespace raylane {

namespace {

std::unique_ptr<const TraceBackend> make_backend(const Scene& scene, const Bvh& bvh,
                                                 TracerBackend backend, Isa isa) {
  switch (backend) {
    case TracerBackend::kPacket:
      return packet_backend(scene, bvh, isa);
    case TracerBackend::kBvh:
      return bvh_reference_backend(scene, bvh);
    case TracerBackend::kScalar:
      return brute_force_backend(scene);
  }
  return packet_backend(scene, bvh, isa);  // not reached: every enumerator is a case
}

}  // namespace

Tracer::Tracer(const Scene& scene, const Bvh& bvh, TracerBackend backend, Isa isa)
    : scene_(scene), backend_(backend), isa_(isa), impl_(make_backend(scene, bvh, backend, isa)) {}

void Tracer::closest(const std::vector<Rayd>& rays, std::vector<Hit>& hits) const {
  TraceScratch scratch;
  impl_->closest(rays, hits, scratch);
}

void Tracer::closest(const RayStream& rays, std::vector<Hit>& hits, std::size_t with_surface,
                     TraceScratch& scratch) const {
  impl_->closest(rays, hits, with_surface, scratch);
}

void Tracer::occluded(const std::vector<Rayd>& rays, const std::vector<PrimRef>& aims,
                      std::vector<uint8_t>& blocked, TraceScratch& scratch) const {
  impl_->occluded(rays, aims, blocked, scratch);
}

void Tracer::occluded(const RayStream& rays, std::vector<uint8_t>& blocked,
                      TraceScratch& scratch) const {
  impl_->occluded(rays, blocked, scratch);
}

void Tracer::closest(const RayStream& rays, HitStream& hits, TraceScratch& scratch) const {
  impl_->closest(rays, hits, scratch);
}

void Tracer::surfaces(const RayStream& rays, const HitStream& hits, std::span<const uint32_t> ray,
                      const SurfaceColumns& out, TraceScratch& scratch) const {
  impl_->surfaces(rays, hits, ray, out, scratch);
}

void Tracer::complete(const Rayd& ray, Hit& h) const {
  if (!h.hit()) return;
  // The ray as the backend traced it: the packet tracer's rays are rounded to float, and the
  // surface is computed for that ray so that t and the point agree.
  const Rayd traced =
      backend_ == TracerBackend::kPacket ? ray_cast<double>(ray_cast<float>(ray)) : ray;
  h.surface = surface_of(scene_, h.prim, traced, h.t);
  h.front_face = dot(traced.d, h.surface.ng) < 0;
}

glm::dvec3 Tracer::hit_point_bound(const Rayd& ray, const Hit& hit) const {
  glm::dvec3 e = hit_point_error(ray, hit.t);
  if (hit.prim.tag() == tag_of<Triangle>)
    e += triangle_vertex_bound(scene_.table<Triangle>(), hit.prim.row());
  return e;
}

Surface surface_of(const Scene& scene, PrimRef prim, const Rayd& ray, double t) {
  return dispatch(prim.tag(), [&](auto kind) {
    return surface_ref(scene.table<decltype(kind)>(), prim.row(), ray, t);
  });
}

void store_surface(const SurfaceColumns& out, std::size_t r, const Scene& scene, PrimRef prim,
                   const Surface& s, const Rayd& ray, double t) {
  out.px[r] = float(s.p.x), out.py[r] = float(s.p.y), out.pz[r] = float(s.p.z);
  out.ngx[r] = float(s.ng.x), out.ngy[r] = float(s.ng.y), out.ngz[r] = float(s.ng.z);
  out.nsx[r] = float(s.ns.x), out.nsy[r] = float(s.ns.y), out.nsz[r] = float(s.ns.z);
  // In double from the double point, then rounded: the bound's 2^-20 covers the rounding.
  glm::dvec3 e = float_hit_point_bound<double>(ray.o, ray.d, t, s.p);
  if (prim.tag() == tag_of<Triangle>)
    e += triangle_vertex_bound(scene.table<Triangle>(), prim.row());
  out.ex[r] = float(e.x), out.ey[r] = float(e.y), out.ez[r] = float(e.z);
  out.cos_ns[r] = dot(s.ns, ray.d);
  out.front[r] = dot(ray.d, s.ng) < 0;
}

}  // namespace raylane
