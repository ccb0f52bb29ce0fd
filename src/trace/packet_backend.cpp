// The packet backend (trace/trace_backend.h): the SIMD tracer on float rays, then the hits'
// surfaces (float lanes for the render's columns where the kind has them, in one pass over the
// rows in order; then kind by kind, in double lanes where the kind has them, by surface_ref
// otherwise), each for the ray as traced, so that t and the point agree.
#include <algorithm>

#include "raylane/prims/prim_list.h"
#include "raylane/trace/simd_tracer.h"
#include "raylane/trace/trace_backend.h"

namespace raylane {

namespace {

class PacketBackend final : public TraceBackend {
 public:
  PacketBackend(const Scene& scene, const Bvh& bvh, Isa isa)
      : scene_(scene), bvh_(bvh), simd_(isa) {}

  void closest(const std::vector<Rayd>& rays, std::vector<Hit>& hits,
               TraceScratch& scratch) const override {
    RayStream& stream = to_stream(rays, scratch);
    stream.aim.clear();  // left by occluded()
    closest(stream, hits, rays.size(), scratch);
  }
  void occluded(const std::vector<Rayd>& rays, const std::vector<PrimRef>& aims,
                std::vector<uint8_t>& blocked, TraceScratch& scratch) const override {
    RayStream& stream = to_stream(rays, scratch);
    stream.aim.resize(aims.empty() ? 0 : rays.size());
    for (std::size_t i = 0; i < stream.aim.size(); ++i)
      stream.aim[i] = aims[i].bits();
    occluded(stream, blocked, scratch);
  }
  void closest(const RayStream& rays, std::vector<Hit>& hits, std::size_t with_surface,
               TraceScratch& scratch) const override;
  void occluded(const RayStream& rays, std::vector<uint8_t>& blocked,
                TraceScratch& scratch) const override {
    simd_.occluded(scene_, bvh_, rays, scratch.hits);
    blocked.resize(rays.size());
    // Through locals, which the compiler vectorises: through the vectors, the byte stores
    // could alias their own pointers, reloaded every row (ten instructions a ray).
    const uint32_t* prim = scratch.hits.prim.data();
    uint8_t* out = blocked.data();
    const std::size_t n = rays.size();
    for (std::size_t i = 0; i < n; ++i)
      out[i] = prim[i] != PrimRef::kInvalidBits;
  }
  void closest(const RayStream& rays, HitStream& hits, TraceScratch&) const override {
    simd_.closest(scene_, bvh_, rays, hits);
  }
  void surfaces(const RayStream& rays, const HitStream& hits, std::span<const uint32_t> ray,
                const SurfaceColumns& out, TraceScratch& scratch) const override;

 private:
  // The double rays rounded to float into the scratch stream, with their times where something
  // moves.
  RayStream& to_stream(const std::vector<Rayd>& rays, TraceScratch& scratch) const {
    RayStream& stream = scratch.rays;
    stream.resize(rays.size());
    stream.time.resize(scene_.moves() ? rays.size() : 0);
    for (std::size_t i = 0; i < rays.size(); ++i)
      stream.set(i, ray_cast<float>(rays[i]));
    return stream;
  }
  // The surfaces of hits[0, n), primitive kind by primitive kind (one branch on the kind per
  // batch, not per hit).
  void complete_by_prim_kind(const RayStream& rays, std::vector<Hit>& hits, std::size_t n,
                             TraceScratch& scratch) const;

  const Scene& scene_;
  const Bvh& bvh_;
  SimdTracer simd_;
};

void PacketBackend::closest(const RayStream& rays, std::vector<Hit>& hits, std::size_t with_surface,
                            TraceScratch& scratch) const {
  const std::size_t n = rays.size();
  hits.resize(n);
  HitStream& out = scratch.hits;
  simd_.closest(scene_, bvh_, rays, out);  // closest hit ignores rays.aim
  // Only prim and t: the surfaces follow for the rays that get one (clearing every 96-byte Hit
  // first would be a pass over the batch that nothing reads).
  for (std::size_t i = 0; i < n; ++i) {
    hits[i].prim = PrimRef::from_bits(out.prim[i]);
    hits[i].t = out.t[i];  // +inf for a miss
  }
  complete_by_prim_kind(rays, hits, std::min(with_surface, n), scratch);
}

// Rows row_of(0), …, row_of(n − 1) grouped by their hit's primitive kind into
// scratch.by_kind: row r where prim_of(r) is valid (a hit), in its kind's list, in order.
template <class RowOf, class PrimOf>
void group_by_prim_kind(std::size_t n, const RowOf& row_of, const PrimOf& prim_of,
                        TraceScratch& scratch) {
  for (auto& list : scratch.by_kind)
    list.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const uint32_t r = row_of(i);
    const PrimRef prim = prim_of(r);
    if (prim.valid()) scratch.by_kind[std::size_t(prim.tag())].push_back(r);
  }
}

void PacketBackend::complete_by_prim_kind(const RayStream& rays, std::vector<Hit>& hits,
                                          std::size_t n, TraceScratch& scratch) const {
  group_by_prim_kind(
      n, [](std::size_t i) { return uint32_t(i); }, [&](uint32_t i) { return hits[i].prim; },
      scratch);
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
      // The float ray from the stream the packet tracer read, not a double ray rounded here:
      // GCC 12's SLP vectoriser dropped the double → float → double round trip when that was
      // inlined into this loop (-O2 and -O3; tests/trace/tracer_test.cpp caught it).
      Rayd traced = ray_cast<double>(rays.get(i));
      h.surface = surface_ref(table, h.prim.row(), traced, h.t);
      h.front_face = dot(traced.d, h.surface.ng) < 0;
    }
  });
}

void PacketBackend::surfaces(const RayStream& rays, const HitStream& hits,
                             std::span<const uint32_t> ray, const SurfaceColumns& out,
                             TraceScratch& scratch) const {
  const uint32_t* prim = hits.prim.data();
  scratch.rest.resize(ray.size());
  const std::size_t rest = simd_.float_surfaces(scene_, rays, ray, hits, out, scratch.rest.data());
  group_by_prim_kind(
      rest, [&](std::size_t i) { return scratch.rest[i]; },
      [&](uint32_t r) { return PrimRef::from_bits(prim[ray[r]]); }, scratch);
  PrimKinds::for_each([&](auto kind) {
    using Kind = decltype(kind);
    const std::vector<uint32_t>& rows = scratch.by_kind[kind_index<Kind>()];
    if constexpr (Kind::surface_in_float_lanes) {
      return;  // written by float_surfaces
    } else if constexpr (Kind::surface_in_lanes) {
      simd_.surfaces(scene_, rays, tag_of<Kind>, rows, ray.data(), hits, out);
      return;
    }
    const typename Kind::Table& table = scene_.table<Kind>();
    for (uint32_t r : rows) {
      const PrimRef p = PrimRef::from_bits(prim[ray[r]]);
      const Rayd traced = ray_cast<double>(rays.get(ray[r]));
      const double t = hits.t[ray[r]];
      store_surface(out, r, scene_, p, surface_ref(table, p.row(), traced, t), traced, t);
    }
  });
}

}  // namespace

std::unique_ptr<const TraceBackend> packet_backend(const Scene& scene, const Bvh& bvh, Isa isa) {
  return std::make_unique<PacketBackend>(scene, bvh, isa);
}

}  // namespace raylane
