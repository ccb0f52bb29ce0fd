#include "raylane/trace/tracer.h"

#include "raylane/prims/prim_list.h"
#include "raylane/trace/brute_force.h"
#include "raylane/trace/bvh_ref.h"

namespace raylane {

namespace {

// The ray as the tracer saw it: SIMD kernels trace rays rounded to float, and the surface is
// computed for that ray so that t and the point agree.
Rayd as_traced(const Rayd& ray, TracerKind kind) {
  return kind == TracerKind::kPacket ? ray_cast<double>(ray_cast<float>(ray)) : ray;
}

}  // namespace

void Tracer::closest(const std::vector<Rayd>& rays, std::vector<Hit>& hits) const {
  TraceScratch scratch;
  closest(rays, hits, rays.size(), scratch);
}

void Tracer::complete(const Rayd& ray, Hit& h) const {
  if (!h.hit()) return;
  Rayd traced = as_traced(ray, kind_);
  h.surface = dispatch(h.prim.tag(), [&](auto kind) {
    return surface_ref(scene_.table<decltype(kind)>(), h.prim.row(), traced, h.t);
  });
  h.front_face = dot(traced.d, h.surface.ng) < 0;
}

void Tracer::closest(const std::vector<Rayd>& rays, std::vector<Hit>& hits,
                     std::size_t with_surface, TraceScratch& scratch) const {
  const std::size_t n = rays.size();
  hits.assign(n, Hit{});
  if (kind_ != TracerKind::kPacket) {
    for (std::size_t i = 0; i < n; ++i)
      hits[i] = kind_ == TracerKind::kBvh ? closest_hit_bvh_ref(scene_, bvh_, rays[i])
                                          : closest_hit_ref(scene_, rays[i]);
    return;
  }
  RayStream& stream = scratch.rays;
  stream.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    stream.set(i, ray_cast<float>(rays[i]));
  HitStream& out = scratch.hits;
  simd_.closest(scene_, bvh_, stream, out);
  for (std::size_t i = 0; i < n; ++i) {
    if (out.prim[i] == PrimRef::kInvalidBits) continue;
    hits[i].prim = PrimRef::from_bits(out.prim[i]);
    hits[i].t = out.t[i];
    if (i < with_surface) complete(rays[i], hits[i]);
  }
}

}  // namespace raylane
