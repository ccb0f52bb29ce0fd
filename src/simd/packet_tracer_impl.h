// The body of the packet tracer, instantiated once per instruction set by
// src/simd/isa_*.cpp. Include from nowhere else.
#pragma once

#include <cfloat>

#include "raylane/trace/packet_tracer.h"
#include "raylane/trace/packet_traverse.h"

namespace raylane::detail {

// Loads rays [i, i + n) into a packet; lanes past n, and invalid rays, are inactive.
template <class A>
RayPacket<A> load_packet(const RayStream& s, std::size_t i, int n, simd::Floats<A>& tmax) {
  using F = simd::Floats<A>;
  constexpr int W = simd::kWidth<A>;
  alignas(64) float buf[8][W];
  const std::vector<float>* cols[8] = {&s.ox, &s.oy, &s.oz, &s.dx, &s.dy, &s.dz, &s.tmin, &s.tmax};
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < W; ++k)
      buf[c][k] = k < n ? (*cols[c])[i + k] : 0.0f;
  RayPacket<A> r;
  r.ox = F::load_aligned(buf[0]), r.oy = F::load_aligned(buf[1]), r.oz = F::load_aligned(buf[2]);
  r.dx = F::load_aligned(buf[3]), r.dy = F::load_aligned(buf[4]), r.dz = F::load_aligned(buf[5]);
  r.tmin = F::load_aligned(buf[6]);
  tmax = F::load_aligned(buf[7]);
  const F one(1.0f), big(FLT_MAX);
  r.inv_dx = one / r.dx, r.inv_dy = one / r.dy, r.inv_dz = one / r.dz;
  // Valid: finite origin and direction (|x| <= FLT_MAX is false for NaN and inf), a non-zero
  // direction, and tmin <= tmax (false for NaN).
  auto finite = [&](const F& v) { return xsimd::abs(v) <= big; };
  F dd = r.dx * r.dx + r.dy * r.dy + r.dz * r.dz;
  r.active = simd::first_lanes<A>(n) & finite(r.ox) & finite(r.oy) & finite(r.oz) & finite(r.dx) &
             finite(r.dy) & finite(r.dz) & (dd > F(0.0f)) & (r.tmin <= tmax);
  return r;
}

// One packet, closest hit or any hit, counted or not.
template <class A>
void traverse(const Scene& scene, const Bvh& bvh, RayPacket<A>& r, HitPacket<A>& h, bool any_hit,
              TraversalCounters* c) {
  if (c) {
    ++c->packets;
    c->rays += uint64_t(__builtin_popcount(simd::bits<A>(r.active)));
    if (any_hit) return traverse_packet<A, true, true>(scene, bvh, r, h, c);
    return traverse_packet<A, false, true>(scene, bvh, r, h, c);
  }
  if (any_hit) return traverse_packet<A, true>(scene, bvh, r, h);
  traverse_packet<A, false>(scene, bvh, r, h);
}

template <class A>
void trace_range(const Scene& scene, const Bvh& bvh, const RayStream& rays, std::size_t begin,
                 std::size_t end, HitStream& hits, bool any_hit, TraversalCounters* counters) {
  using F = simd::Floats<A>;
  constexpr int W = simd::kWidth<A>;
  const F inf(std::numeric_limits<float>::infinity());
  if (counters) counters->width = W;
  for (std::size_t i = begin; i < end; i += W) {
    int n = int(std::min<std::size_t>(W, end - i));
    HitPacket<A> h;
    RayPacket<A> r = load_packet<A>(rays, i, n, h.t);
    h.prim = simd::Ints<A>(int32_t(PrimRef::kInvalidBits));
    h.found = F(0.0f) != F(0.0f);
    if (simd::any<A>(r.active)) traverse<A>(scene, bvh, r, h, any_hit, counters);
    alignas(64) float t[W];
    alignas(64) int32_t prim[W];
    simd::Ints<A> occluded_bits(0);
    simd::store<A>(t, simd::select<A>(h.found, h.t, inf));
    simd::store<A>(prim, any_hit ? simd::select<A>(h.found, occluded_bits, h.prim) : h.prim);
    for (int k = 0; k < n; ++k) {
      hits.t[i + k] = t[k];
      hits.prim[i + k] = uint32_t(prim[k]);
    }
  }
}

}  // namespace raylane::detail
