#include "raylane/trace/tracer.h"

#include "raylane/prims/prim_list.h"
#include "raylane/trace/brute_force.h"
#include "raylane/trace/bvh_ref.h"

namespace raylane {

void Tracer::closest(const std::vector<Rayd>& rays, std::vector<Hit>& hits) const {
  const std::size_t n = rays.size();
  hits.assign(n, Hit{});
  if (kind_ != TracerKind::kPacket) {
    for (std::size_t i = 0; i < n; ++i)
      hits[i] = kind_ == TracerKind::kBvh ? closest_hit_bvh_ref(scene_, bvh_, rays[i])
                                          : closest_hit_ref(scene_, rays[i]);
    return;
  }
  RayStream stream;
  stream.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    stream.set(i, ray_cast<float>(rays[i]));
  HitStream out;
  simd_.closest(scene_, bvh_, stream, out);
  for (std::size_t i = 0; i < n; ++i) {
    if (out.prim[i] == PrimRef::kInvalidBits) continue;
    Hit& h = hits[i];
    Rayd traced = ray_cast<double>(stream.get(i));
    h.prim = PrimRef::from_bits(out.prim[i]);
    h.t = out.t[i];
    h.surface = dispatch(h.prim.tag(), [&](auto kind) {
      return surface_ref(scene_.table<decltype(kind)>(), h.prim.row(), traced, h.t);
    });
    h.front_face = dot(traced.d, h.surface.ng) < 0;
  }
}

}  // namespace raylane
