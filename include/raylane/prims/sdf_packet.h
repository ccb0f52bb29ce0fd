// Signed-distance blocks: the SIMD kernel (sdf.h has the table and the reference marcher).
// Lane code: included only through prims/prim_packets.h by the SIMD tracer's per-ISA
// translation units.
//
// Sphere tracing in float lanes (Hart 1996, "Sphere tracing", §2-3): the rays of a packet march
// one block together from where each enters its bounds, by the block's distance evaluated in
// lanes (sdf_lanes.h), and each lane retires when it hits — |distance| below the tolerance of
// sdf.h, which scales with the distance travelled and is 8 float ulps of the point at least, so
// float coordinates suffice — or leaves the bounds or its nearest hit so far, or runs out of
// steps. The rules are the reference's (sdf.cpp, Sdf::hit_ref): armed at once when entering the
// bounds, else only once out of the band |distance| < tolerance (a secondary ray leaving the
// surface), by |distance| so a ray from inside finds where it leaves.
//
// Steps are over-relaxed (Keinert et al. 2014, "Enhanced Sphere Tracing", §3.1): a lane steps
// ω·|distance| and checks at the next point that the two unbounding spheres overlap,
// r_prev + r ≥ step (the segment between is then free of the surface); where they do not, or
// the distance changed sign (a step across a surface met head on makes the overlap an
// equality), it goes back and takes the plain step, and marches plainly from there on. A hit
// counts only at a point so checked; a relaxed step that would leave the bounds is taken plainly
// instead, so no surface before the exit is skipped. Nothing is allocated.
#pragma once

#include <limits>

#include "raylane/prims/prim_list.h"
#include "raylane/prims/sdf_lanes.h"
#include "raylane/simd/packet.h"

namespace raylane {

// Keinert et al. 2014 (§3.1) use ω of about 1.2-2. On the pixels of scenes/sdf.scn, whose
// marches start at tight bounds and mostly meet surfaces head on (where a relaxed step fails
// and the march goes on plainly), 1.2 takes 5 % fewer steps than plain marching and 1.4-1.8
// take more (tests/trace/sdf_packet_test.cpp, SdfMarch; bench/README.md, "SDF blocks").
inline constexpr float kSdfOverRelaxation = 1.2f;

namespace detail {

// A march's outcome per lane.
template <class A>
struct SdfMarchLanes {
  simd::Floats<A> t;          // where it hit (inf elsewhere)
  simd::Mask<A> hit;          // lanes that hit
  uint32_t steps = 0;         // Σ over lanes of the distance evaluations
  uint32_t marches = 0;       // lanes that marched (met the bounds within their segment)
  uint32_t out_of_steps = 0;  // lanes still marching after kSdfMaxSteps: misses by steps
};

// Block row `row` along the rays of `lanes`, up to each lane's tmax (exclusive); `omega` 1
// marches plainly.
template <class A>
SdfMarchLanes<A> sdf_march_lanes(const SdfTable& s, const SdfBlockLanes& blk, uint32_t row,
                                 const simd::Mask<A>& lanes, const RayPacket<A>& r,
                                 const simd::Floats<A>& tmax, float omega = kSdfOverRelaxation) {
  using F = simd::Floats<A>;
  using M = simd::Mask<A>;
  const F inf(std::numeric_limits<float>::infinity()), zero(0.0f);
  // The bounds' slabs (the near plane by the sign of 1/d; box_packet.h), NaN-keeping extrema.
  F tn = -inf, tf = inf;
  auto slab = [&](float lo, float hi, const F& o, const F& inv) {
    F tlo = (F(lo) - o) * inv, thi = (F(hi) - o) * inv;
    M neg = inv < zero;
    tn = simd::max_keep<A>(simd::select<A>(neg, thi, tlo), tn);
    tf = simd::min_keep<A>(simd::select<A>(neg, tlo, thi), tf);
  };
  slab(s.lox[row], s.hix[row], r.ox, r.inv_dx);
  slab(s.loy[row], s.hiy[row], r.oy, r.inv_dy);
  slab(s.loz[row], s.hiz[row], r.oz, r.inv_dz);
  M armed = tn > r.tmin;
  const F t0 = simd::max_keep<A>(tn, r.tmin), t1 = simd::min_keep<A>(tf, tmax);
  const F len = simd::sqrt<A>(r.dx * r.dx + r.dy * r.dy + r.dz * r.dz);
  const F o =
      simd::max_keep<A>(xsimd::abs(r.ox), simd::max_keep<A>(xsimd::abs(r.oy), xsimd::abs(r.oz)));
  const F inv_len = F(1.0f) / len;
  M live = lanes & (t0 <= t1) & (t0 < inf) & (len > zero) & (len < inf) & (o < inf);

  SdfMarchLanes<A> out{inf, live & !live};
  out.marches = uint32_t(simd::popcount<A>(simd::bits<A>(live)));
  F t = t0;
  // The last point checked: its t, |distance| and sign, the plain step from it (in t), and the
  // step taken from it (along the ray) when that was relaxed.
  F t_prev = t0, r_prev = zero, plain_prev = zero, step_prev = zero;
  M neg_prev = live & !live, relaxed = neg_prev;
  F w(omega);
  for (int step = 0; step < kSdfMaxSteps && simd::any<A>(live); ++step) {
    out.steps += uint32_t(simd::popcount<A>(simd::bits<A>(live)));
    simd::FloatVec3<A> p{simd::fma<A>(r.dx, t, r.ox), simd::fma<A>(r.dy, t, r.oy),
                         simd::fma<A>(r.dz, t, r.oz)};
    const F d = blk.distance<A>(p);
    live = live & (d == d);  // a NaN distance ends the march: a miss
    const F rad = xsimd::abs(d);
    const M neg = d < zero;
    // Keinert's check: the spheres of the last two points overlap and no sign changed.
    const M failed =
        live & relaxed & ((rad + r_prev < step_prev) | (neg & (!neg_prev)) | (neg_prev & (!neg)));
    const M ok = live & !failed;
    const F s_len = t * len;
    const F tol = F(1e-4f) * s_len + F(0x1p-20f) * (o + s_len);
    const M in_band = rad < tol;
    const M hit = ok & armed & in_band;
    out.t = simd::select<A>(hit, t, out.t);
    out.hit = out.hit | hit;
    live = live & !hit;
    armed = armed | (ok & !in_band);
    // From a checked point: relaxed where armed and ω > 1, unless that leaves the segment.
    const F plain = simd::max_keep<A>(rad, tol) * inv_len;
    const M relax = ok & armed & (w > F(1.0f));
    F next = t + simd::select<A>(relax, w * plain, plain);
    const M relax_ok = relax & (next <= t1);
    next = simd::select<A>(relax & !relax_ok, t + plain, next);
    // From a failed one: back to the plain step from the last checked point, plainly after.
    next = simd::select<A>(failed, t_prev + plain_prev, next);
    w = simd::select<A>(failed, F(1.0f), w);
    t_prev = simd::select<A>(ok, t, t_prev), r_prev = simd::select<A>(ok, rad, r_prev);
    plain_prev = simd::select<A>(ok, plain, plain_prev);
    step_prev = simd::select<A>(ok, (next - t) * len, step_prev);
    neg_prev = (ok & neg) | ((!ok) & neg_prev);
    relaxed = relax_ok;
    t = next;
    live = live & (t <= t1);
  }
  out.out_of_steps = uint32_t(simd::popcount<A>(simd::bits<A>(live)));
  return out;
}

// Block `row` against the lanes of `lanes`: commits each hit nearer than the lane's closest so
// far, naming the leaf nearest the hit point.
template <class A>
inline void sdf_block_lanes(const SdfTable& s, uint32_t row, const simd::Mask<A>& lanes,
                            const RayPacket<A>& r, HitPacket<A>& h) {
  const SdfBlockLanes blk(s, s.block[row]);
  SdfMarchLanes<A> m = sdf_march_lanes<A>(s, blk, row, lanes, r, h.t);
  sdf_count_marches({m.marches, m.steps, m.out_of_steps});
  const simd::Mask<A> hit = m.hit & (m.t > r.tmin) & (m.t < h.t);
  if (simd::none<A>(hit)) return;
  simd::FloatVec3<A> p{simd::fma<A>(r.dx, m.t, r.ox), simd::fma<A>(r.dy, m.t, r.oy),
                       simd::fma<A>(r.dz, m.t, r.oz)};
  simd::Ints<A> leaf = blk.nearest_leaf<A>(p);
  commit_hit<A>(m.t, hit, simd::Ints<A>(prim_bits(tag_of<Sdf>, 0)) + leaf, h);
}

}  // namespace detail

// The packet kernel. Rays in lanes: one block per step. One ray in every lane (the single-ray
// traversal): each block of the run with the ray in lane 0 alone (the blocks' programs differ).
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
