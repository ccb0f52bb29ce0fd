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

// surface_ref (box.h) for one hit per lane: the face by the same selects (entry: the last near
// plane, exit: the first far plane, ties to the lowest axis), its unit normal, the point
// snapped onto it.
template <class A>
SurfaceLanes<A> surface_lanes(const BoxTable& b, const uint32_t* rows, const HitRayLanes<A>& r) {
  using D = simd::Doubles<A>;
  const simd::DoubleVec3<A> lo = load_rows3<A>(b.lox, b.loy, b.loz, rows);
  const simd::DoubleVec3<A> hi = load_rows3<A>(b.hix, b.hiy, b.hiz, rows);
  const D* los[3] = {&lo.x, &lo.y, &lo.z};
  const D* his[3] = {&hi.x, &hi.y, &hi.z};
  const D* os[3] = {&r.o.x, &r.o.y, &r.o.z};
  const D* ds[3] = {&r.d.x, &r.d.y, &r.d.z};
  D entry(-std::numeric_limits<double>::infinity()), exit(std::numeric_limits<double>::infinity());
  D entry_axis(-1.0), exit_axis(-1.0);
  for (int k = 0; k < 3; ++k) {
    D inv = D(1.0) / *ds[k];
    auto neg = simd::sign_bit<A>(*ds[k]);
    D tn = (xsimd::select(neg, *his[k], *los[k]) - *os[k]) * inv;
    D tf = (xsimd::select(neg, *los[k], *his[k]) - *os[k]) * inv;
    auto nearer = tn > entry, farther = tf < exit;
    entry = xsimd::select(nearer, tn, entry);
    entry_axis = xsimd::select(nearer, D(double(k)), entry_axis);
    exit = xsimd::select(farther, tf, exit);
    exit_axis = xsimd::select(farther, D(double(k)), exit_axis);
  }
  auto entering = (entry_axis >= D(0.0)) &
                  ((exit_axis < D(0.0)) | (xsimd::abs(r.t - entry) <= xsimd::abs(r.t - exit)));
  D axis =
      xsimd::select(entering, entry_axis, xsimd::select(exit_axis >= D(0.0), exit_axis, D(0.0)));
  SurfaceLanes<A> out{r.at(), {}};
  D* ps[3] = {&out.p.x, &out.p.y, &out.p.z};
  D* ns[3] = {&out.n.x, &out.n.y, &out.n.z};
  for (int k = 0; k < 3; ++k) {
    auto on = axis == D(double(k));
    // Entering, the face looks back at the ray; leaving, it looks along it. By selects: xsimd
    // 8.1's `^` of two AVX-512 masks and `!=` of two SSE masks both compute their OR.
    auto neg = simd::sign_bit<A>(*ds[k]);
    D sign = xsimd::select(entering, xsimd::select(neg, D(1.0), D(-1.0)),
                           xsimd::select(neg, D(-1.0), D(1.0)));
    *ns[k] = xsimd::select(on, sign, D(0.0));
    *ps[k] = xsimd::select(on, xsimd::select(sign > D(0.0), *his[k], *los[k]), *ps[k]);
  }
  return out;
}

}  // namespace raylane
