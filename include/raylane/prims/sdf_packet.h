// Signed-distance blocks in the packet tracer (sdf.h has the table and the reference). Lane
// code: included only through prims/prim_packets.h by the SIMD tracer's per-ISA translation
// units.
//
// Each active lane's ray is marched by the double reference (Sdf::hit_ref), as the reference
// tracers do, and the hit committed when its t, rounded to float, is beyond tmin and nearer than
// the lane's closest hit so far. A march in float lanes is not written yet: the lanes are the
// reference's answers exactly. Nothing is allocated.
#pragma once

#include "raylane/prims/prim_list.h"
#include "raylane/simd/packet.h"

namespace raylane {

namespace detail {

// Block `row` against the lanes of `lanes`.
template <class A>
inline void sdf_block_lanes(const SdfTable& s, uint32_t row, const simd::Mask<A>& lanes,
                            const RayPacket<A>& r, HitPacket<A>& h) {
  constexpr int W = simd::kWidth<A>;
  alignas(64) float ox[W], oy[W], oz[W], dx[W], dy[W], dz[W], tmin[W], tmax[W];
  alignas(64) int32_t prim[W];
  simd::store<A>(ox, r.ox), simd::store<A>(oy, r.oy), simd::store<A>(oz, r.oz);
  simd::store<A>(dx, r.dx), simd::store<A>(dy, r.dy), simd::store<A>(dz, r.dz);
  simd::store<A>(tmin, r.tmin), simd::store<A>(tmax, h.t), simd::store<A>(prim, h.prim);
  const uint32_t live = simd::bits<A>(lanes);
  bool any = false;
  for (int i = 0; i < W; ++i) {
    if (!((live >> i) & 1u)) continue;
    Rayd ray;
    ray.o = {ox[i], oy[i], oz[i]}, ray.d = {dx[i], dy[i], dz[i]};
    ray.tmin = tmin[i], ray.tmax = tmax[i];
    Sdf::LeafHit hit = Sdf::hit_ref(s, row, ray);
    const float t = float(hit.t);
    if (!(t > tmin[i] && t < tmax[i])) continue;
    tmax[i] = t, prim[i] = int32_t(prim_bits(tag_of<Sdf>, hit.row));
    any = true;
  }
  if (!any) return;
  const simd::Floats<A> t = simd::load<A>(tmax);
  commit_hit<A>(t, t < h.t, simd::load<A>(prim), h);
}

}  // namespace detail

// The packet kernel. Rays in lanes: one block per step. One ray in every lane (the single-ray
// traversal): each block of the run with the ray in lane 0 alone.
template <class A, class Rows>
[[gnu::always_inline]] inline void intersect_packet(const SdfTable& s, Rows rows,
                                                    const RayPacket<A>& r, HitPacket<A>& h) {
  for (; rows.more(); rows.next()) {
    if constexpr (Rows::kOneRay) {
      const uint32_t end = std::min<uint32_t>(rows.end, rows.i + simd::kWidth<A>);
      for (uint32_t b = rows.i; b < end; ++b)
        detail::sdf_block_lanes<A>(s, b, simd::first_lanes<A>(1), r, h);
    } else {
      detail::sdf_block_lanes<A>(s, rows.i, rows.mask(), r, h);
    }
  }
}

}  // namespace raylane
