// Boxes: the SIMD kernel (box.h has the table and the reference). Lane code: included
// only through prims/prim_packets.h by the SIMD tracer's per-ISA translation units.
#pragma once

#include "raylane/prims/prim_list.h"
#include "raylane/trace/packet.h"

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

}  // namespace raylane
