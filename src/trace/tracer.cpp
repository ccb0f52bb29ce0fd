#include "raylane/trace/tracer.h"

#include <cassert>

#include <algorithm>
#include <string>

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

bool Tracer::occluded_ref(const Rayd& ray, PrimRef aim) const {
  const bool bvh = kind_ == TracerKind::kBvh;
  if (!aim.valid()) return bvh ? any_hit_bvh_ref(scene_, bvh_, ray) : any_hit_ref(scene_, ray);
  Hit h = bvh ? closest_hit_bvh_ref(scene_, bvh_, ray) : closest_hit_ref(scene_, ray);
  return h.hit() && h.prim != aim;
}

void Tracer::occluded(const std::vector<Rayd>& rays, const std::vector<PrimRef>& aims,
                      std::vector<uint8_t>& blocked, TraceScratch& scratch) const {
  const std::size_t n = rays.size();
  assert(aims.empty() || aims.size() == n);  // the contract in tracer.h
  if (kind_ != TracerKind::kPacket) {
    blocked.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      blocked[i] = occluded_ref(rays[i], aims.empty() ? PrimRef::invalid() : aims[i]);
    return;
  }
  RayStream& stream = scratch.rays;
  stream.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    stream.set(i, ray_cast<float>(rays[i]));
  stream.aim.resize(aims.empty() ? 0 : n);
  for (std::size_t i = 0; i < stream.aim.size(); ++i)
    stream.aim[i] = aims[i].bits();
  occluded(stream, blocked, scratch);
}

void Tracer::occluded(const RayStream& rays, std::vector<uint8_t>& blocked,
                      TraceScratch& scratch) const {
  const std::size_t n = rays.size();
  blocked.resize(n);
  if (kind_ != TracerKind::kPacket) {
    const bool aimed = !rays.aim.empty();
    for (std::size_t i = 0; i < n; ++i)
      blocked[i] = occluded_ref(ray_cast<double>(rays.get(i)),
                                aimed ? PrimRef::from_bits(rays.aim[i]) : PrimRef::invalid());
    return;
  }
  simd_.occluded(scene_, bvh_, rays, scratch.hits);
  for (std::size_t i = 0; i < n; ++i)
    blocked[i] = scratch.hits.prim[i] != PrimRef::kInvalidBits;
}

void Tracer::complete_by_kind(const RayStream& rays, std::vector<Hit>& hits, std::size_t n,
                              TraceScratch& scratch) const {
  for (auto& rows : scratch.by_kind)
    rows.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (hits[i].hit()) scratch.by_kind[std::size_t(hits[i].prim.tag())].push_back(uint32_t(i));
  PrimKinds::for_each([&](auto kind) {
    using Kind = decltype(kind);
    const std::vector<uint32_t>& rows = scratch.by_kind[kind_index<Kind>()];
    if constexpr (Kind::surface_in_lanes) {
      simd_.surfaces(scene_, rays, tag_of<Kind>, rows, hits.data());
      return;
    }
    const typename Kind::Table& table = scene_.table<Kind>();
    for (uint32_t i : rows) {
      Hit& h = hits[i];
      // The float ray from the stream the packet tracer read, not as_traced(rays[i]): GCC 12's
      // SLP vectoriser dropped the double → float → double round trip when as_traced was
      // inlined into this loop (-O2 and -O3; tests/trace/tracer_test.cpp caught it).
      Rayd traced = ray_cast<double>(rays.get(i));
      h.surface = surface_ref(table, h.prim.row(), traced, h.t);
      h.front_face = dot(traced.d, h.surface.ng) < 0;
    }
  });
}

namespace {

// One surface into row r of `out`, from a Surface record.
void store_surface(const SurfaceColumns& out, std::size_t r, const Surface& s,
                   const glm::dvec3& d) {
  out.px[r] = s.p.x, out.py[r] = s.p.y, out.pz[r] = s.p.z;
  out.ngx[r] = s.ng.x, out.ngy[r] = s.ng.y, out.ngz[r] = s.ng.z;
  out.nsx[r] = float(s.ns.x), out.nsy[r] = float(s.ns.y), out.nsz[r] = float(s.ns.z);
  out.cos_ns[r] = dot(s.ns, d);
  out.front[r] = dot(d, s.ng) < 0;
}

}  // namespace

void Tracer::surfaces(const RayStream& rays, const std::vector<Hit>& hits,
                      std::span<const uint32_t> ray, const SurfaceColumns& out,
                      TraceScratch& scratch) const {
  if (kind_ != TracerKind::kPacket) {  // the references' hits come with their surfaces
    for (std::size_t r = 0; r < ray.size(); ++r)
      store_surface(out, r, hits[ray[r]].surface, ray_cast<double>(rays.get(ray[r])).d);
    return;
  }
  for (auto& rows : scratch.by_kind)
    rows.clear();
  for (std::size_t r = 0; r < ray.size(); ++r)
    scratch.by_kind[std::size_t(hits[ray[r]].prim.tag())].push_back(uint32_t(r));
  PrimKinds::for_each([&](auto kind) {
    using Kind = decltype(kind);
    const std::vector<uint32_t>& rows = scratch.by_kind[kind_index<Kind>()];
    if constexpr (Kind::surface_in_lanes) {
      simd_.surfaces(scene_, rays, tag_of<Kind>, rows, ray.data(), hits.data(), out);
      return;
    }
    const typename Kind::Table& table = scene_.table<Kind>();
    for (uint32_t r : rows) {
      const Hit& h = hits[ray[r]];
      const Rayd traced = ray_cast<double>(rays.get(ray[r]));
      store_surface(out, r, surface_ref(table, h.prim.row(), traced, h.t), traced.d);
    }
  });
}

void Tracer::closest(const std::vector<Rayd>& rays, std::vector<Hit>& hits,
                     std::size_t with_surface, TraceScratch& scratch) const {
  const std::size_t n = rays.size();
  if (kind_ != TracerKind::kPacket) {  // the references trace the double rays as given
    hits.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      hits[i] = kind_ == TracerKind::kBvh ? closest_hit_bvh_ref(scene_, bvh_, rays[i])
                                          : closest_hit_ref(scene_, rays[i]);
    return;
  }
  RayStream& stream = scratch.rays;
  stream.resize(n);
  stream.aim.clear();  // left by occluded()
  for (std::size_t i = 0; i < n; ++i)
    stream.set(i, ray_cast<float>(rays[i]));
  closest(stream, hits, with_surface, scratch);
}

void Tracer::closest(const RayStream& rays, std::vector<Hit>& hits, std::size_t with_surface,
                     TraceScratch& scratch) const {
  const std::size_t n = rays.size();
  hits.resize(n);
  if (kind_ != TracerKind::kPacket) {
    for (std::size_t i = 0; i < n; ++i) {
      const Rayd ray = ray_cast<double>(rays.get(i));
      hits[i] = kind_ == TracerKind::kBvh ? closest_hit_bvh_ref(scene_, bvh_, ray)
                                          : closest_hit_ref(scene_, ray);
    }
    return;
  }
  HitStream& out = scratch.hits;
  simd_.closest(scene_, bvh_, rays, out);  // closest hit ignores rays.aim
  // Only prim and t: the surfaces follow for the rays that get one (clearing every 96-byte Hit
  // first would be a pass over the batch that nothing reads).
  for (std::size_t i = 0; i < n; ++i) {
    hits[i].prim = PrimRef::from_bits(out.prim[i]);
    hits[i].t = out.t[i];  // +inf for a miss
  }
  complete_by_kind(rays, hits, std::min(with_surface, n), scratch);
}

}  // namespace raylane
