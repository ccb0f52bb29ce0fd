// Packet traversal of the BVH: W rays in lanes visit a node together when any active lane's
// segment overlaps its box (design.md, "Packets"). Included only by the per-ISA translation
// units, which instantiate it for their instruction set.
#pragma once

#include <cmath>
#include <cstddef>

#include "raylane/bvh/bvh.h"
#include "raylane/core/float_util.h"
#include "raylane/prims/prim_list.h"
#include "raylane/scene/scene.h"
#include "raylane/trace/packet.h"
#include "raylane/trace/traversal_counters.h"

namespace raylane {

// Which lanes' segments (tmin, tfar) overlap a node box. Closed box, NaN-keeping extrema
// (a ray lying in a slab plane keeps the accumulator: hard-cases B4), near and far planes
// chosen by the sign of 1/d, which is the sign of d even for ±0 (B3) — loaded as such when
// the lanes agree on it (RayPacket::sides), selected per lane otherwise. Each t carries three
// roundings (difference, reciprocal, product); the far end is widened by 2·γ3 of its size so
// that rounding never closes an overlap (Ize 2013, "Robust BVH Ray Traversal"; pbrt-v4
// Bounds3::IntersectP). The widening x + 2γ3|x| is monotone, so it is applied once to the
// smallest far value rather than to each; that widens tfar too, which can only add a visit.
template <class A, bool kSameSides>
[[gnu::always_inline]] inline simd::Mask<A> node_overlap(const BvhNode& n, const RayPacket<A>& r,
                                                         const simd::Floats<A>& tfar) {
  using F = simd::Floats<A>;
  static_assert(offsetof(BvhNode, hi) == 3 * sizeof(float));
  const F slack(float(2 * gamma_float(3)));
  const SlabSides<A>& sides = r.sides;
  const float* planes = n.lo;  // lo[0..2], then hi[0..2]
  F t0 = r.tmin, t1 = tfar;
  auto axis = [&](int k, const F& o, const F& inv) {
    F near, far;
    if constexpr (kSameSides) {
      near = F(planes[sides.near[k]]), far = F(planes[sides.far[k]]);
    } else {
      near = simd::select<A>(sides.hi_first[k], F(n.hi[k]), F(n.lo[k]));
      far = simd::select<A>(sides.hi_first[k], F(n.lo[k]), F(n.hi[k]));
    }
    t0 = simd::max_keep<A>((near - o) * inv, t0);
    t1 = simd::min_keep<A>((far - o) * inv, t1);
  };
  axis(0, r.ox, r.inv_dx);
  axis(1, r.oy, r.inv_dy);
  axis(2, r.oz, r.inv_dz);
  t1 = simd::fma<A>(xsimd::abs(t1), slack, t1);
  return (t0 <= t1) & r.active;
}

// Tests `lanes` of the packet against the rows of one leaf: runs of refs of one kind, whose
// rows are contiguous because the tables were permuted into leaf order.
template <class A>
inline void intersect_leaf(const Scene& scene, const Bvh& bvh, const BvhNode& leaf,
                           const RayPacket<A>& r, const simd::Mask<A>& lanes, HitPacket<A>& h) {
  uint32_t i = leaf.index, end = leaf.index + leaf.count;
  while (i < end) {
    PrimRef first = bvh.refs[i];
    uint32_t j = i + 1;
    while (j < end && bvh.refs[j].tag() == first.tag())
      ++j;
    uint32_t row_begin = first.row(), row_end = first.row() + (j - i);
    dispatch(first.tag(), [&](auto kind) {
      using Kind = decltype(kind);
      intersect_packet<A>(scene.table<Kind>(), LanesAreRays<A>{row_begin, row_end, lanes}, r, h);
    });
    i = j;
  }
}

// Closest hit (kAnyHit = false) or occlusion (true) for one packet; h.t starts at tmax.
// kCount = true is the instrumented copy used by the benchmark; `c` is unused otherwise.
// kSameSides: every lane meets each slab from the same side (RayPacket::sides).
template <class A, bool kAnyHit, bool kCount, bool kSameSides>
inline void traverse_packet_loop(const Scene& scene, const Bvh& bvh, RayPacket<A>& r,
                                 HitPacket<A>& h, TraversalCounters* c) {
  uint32_t stack[kBvhStackSize];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& n = bvh.nodes[stack[--top]];
    simd::Mask<A> lanes = node_overlap<A, kSameSides>(n, r, h.t);
    if constexpr (kCount) {
      ++c->node_tests;
      c->lanes_active += uint64_t(__builtin_popcount(simd::bits<A>(r.active)));
      c->lanes_overlap += uint64_t(__builtin_popcount(simd::bits<A>(lanes)));
    }
    if (simd::none<A>(lanes)) continue;
    if (n.is_leaf()) {
      if constexpr (kCount) ++c->leaf_visits, c->prim_tests += n.count;
      intersect_leaf<A>(scene, bvh, n, r, lanes, h);
      if constexpr (kAnyHit) {
        r.active = r.active & !h.found;
        if (simd::none<A>(r.active)) return;
      }
      continue;
    }
    // Near child first, judged by the direction of the first overlapping lane.
    uint32_t lane = uint32_t(__builtin_ctz(simd::bits<A>(lanes)));
    bool left_first = !((r.sides.hi_first_bits[n.axis] >> lane) & 1u);
    stack[top++] = left_first ? n.index + 1 : n.index;
    stack[top++] = left_first ? n.index : n.index + 1;
  }
}

template <class A, bool kAnyHit, bool kCount = false>
inline void traverse_packet(const Scene& scene, const Bvh& bvh, RayPacket<A>& r, HitPacket<A>& h,
                            TraversalCounters* c = nullptr) {
  if (bvh.empty()) return;
  if (r.sides.uniform) return traverse_packet_loop<A, kAnyHit, kCount, true>(scene, bvh, r, h, c);
  traverse_packet_loop<A, kAnyHit, kCount, false>(scene, bvh, r, h, c);
}

}  // namespace raylane
