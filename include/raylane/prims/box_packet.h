// Boxes: the SIMD kernel (box.h has the table and the reference). Lane code: included
// only through prims/prim_packets.h by the SIMD tracer's per-ISA translation units.
#pragma once

#include "raylane/prims/prim_list.h"
#include "raylane/simd/packet.h"
#include "raylane/simd/surface_lanes.h"

namespace raylane {

// The packet kernel: slabs in float with the reference's policy — closed box, NaN-keeping
// extrema, near/far by the sign of 1/d (docs/hard-cases.md B3, B4). The box corners are exact
// floats, and t is as exact as float allows, so no slack is added here (slack belongs to BVH
// nodes).
template <class A, class Rows>
[[gnu::always_inline]] inline void intersect_packet(const BoxTable& b, Rows rows,
                                                    const RayPacket<A>& r, HitPacket<A>& h) {
  using F = simd::Floats<A>;
  const auto neg_x = r.inv_dx < F(0.0f), neg_y = r.inv_dy < F(0.0f), neg_z = r.inv_dz < F(0.0f);
  const F inf(std::numeric_limits<float>::infinity());
  for (; rows.more(); rows.next()) {
    F t0 = -inf, t1 = inf;
    auto slab = [&](const F& lo, const F& hi, const F& o, const F& inv, const simd::Mask<A>& neg) {
      F tlo = (lo - o) * inv, thi = (hi - o) * inv;
      t0 = simd::max_keep<A>(simd::select<A>(neg, thi, tlo), t0);
      t1 = simd::min_keep<A>(simd::select<A>(neg, tlo, thi), t1);
    };
    slab(rows.col(b.lox), rows.col(b.hix), r.ox, r.inv_dx, neg_x);
    slab(rows.col(b.loy), rows.col(b.hiy), r.oy, r.inv_dy, neg_y);
    slab(rows.col(b.loz), rows.col(b.hiz), r.oz, r.inv_dz, neg_z);
    commit_solid_hit<A>(t0, t1, r, rows.mask() & (t0 <= t1), rows.bits(tag_of<Box>), h);
  }
}

// box_surface (box.h) for one hit per double lane: surface_ref's answers bit for bit.
template <class A>
SurfaceLanes<A> surface_lanes(const BoxTable& b, const uint32_t* rows, const HitRayLanes<A>& r) {
  const simd::DoubleVec3<A> lo = load_rows3<A>(b.lox, b.loy, b.loz, rows);
  const simd::DoubleVec3<A> hi = load_rows3<A>(b.hix, b.hiy, b.hiz, rows);
  const BoxSurface<simd::DoubleVec3<A>> s = box_surface<simd::Doubles<A>>(lo, hi, r.o, r.d, r.t);
  return {s.p, s.n};
}

// box_surface for one hit per float lane, with its bound (box_point_bound).
template <class A>
[[gnu::always_inline]] inline FloatSurfaceLanes<A> surface_float_lanes(
    const BoxTable& b, const simd::Ints<A>& rows, const FloatHitRayLanes<A>& r) {
  const simd::FloatVec3<A> lo = read_rows3<A>(b.lox, b.loy, b.loz, rows);
  const simd::FloatVec3<A> hi = read_rows3<A>(b.hix, b.hiy, b.hiz, rows);
  const BoxSurface<simd::FloatVec3<A>> s = box_surface<simd::Floats<A>>(lo, hi, r.o, r.d, r.t);
  return surface_lanes_of<A>(s.p, s.n, s.n,
                             box_point_bound<simd::Floats<A>>(lo, hi, r.o, r.d, r.t, s));
}

}  // namespace raylane
