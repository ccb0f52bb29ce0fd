// Packet traversal of the BVH: W rays in lanes visit a node together when any active lane's
// segment overlaps its box (design.md, "Packets"). Included only by the per-ISA translation
// units, which instantiate it for their instruction set.
#pragma once

#include <cmath>

#include "raylane/bvh/bvh.h"
#include "raylane/core/float_util.h"
#include "raylane/prims/prim_list.h"
#include "raylane/scene/scene.h"
#include "raylane/trace/packet.h"
#include "raylane/trace/traversal_counters.h"

namespace raylane {

// Which lanes' segments (tmin, tfar) overlap a node box. Closed box, NaN-keeping extrema
// (a ray lying in a slab plane keeps the accumulator: hard-cases B4), near/far chosen by the
// sign of 1/d, which is the sign of d even for ±0 (B3). Each t carries three roundings
// (difference, reciprocal, product); the far value is widened by 2·γ3 of its size so that
// rounding never closes an overlap (Ize 2013, "Robust BVH Ray Traversal"; pbrt-v4
// Bounds3::IntersectP).
template <class A>
inline simd::Mask<A> node_overlap(const BvhNode& n, const RayPacket<A>& r,
                                  const simd::Floats<A>& tfar, simd::Floats<A>* tnear_out) {
  using F = simd::Floats<A>;
  const F slack(float(2 * gamma_float(3)));
  F t0 = r.tmin, t1 = tfar;
  auto axis = [&](float lo, float hi, const F& o, const F& inv) {
    F tlo = (F(lo) - o) * inv;
    F thi = (F(hi) - o) * inv;
    auto neg = inv < F(0.0f);
    F near = simd::select<A>(neg, thi, tlo);
    F far = simd::select<A>(neg, tlo, thi);
    far = simd::fma<A>(xsimd::abs(far), slack, far);
    t0 = simd::max_keep<A>(near, t0);
    t1 = simd::min_keep<A>(far, t1);
  };
  axis(n.lo[0], n.hi[0], r.ox, r.inv_dx);
  axis(n.lo[1], n.hi[1], r.oy, r.inv_dy);
  axis(n.lo[2], n.hi[2], r.oz, r.inv_dz);
  if (tnear_out) *tnear_out = t0;
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
template <class A, bool kAnyHit, bool kCount = false>
inline void traverse_packet(const Scene& scene, const Bvh& bvh, RayPacket<A>& r, HitPacket<A>& h,
                            TraversalCounters* c = nullptr) {
  using F = simd::Floats<A>;
  if (bvh.empty()) return;
  uint32_t stack[kBvhStackSize];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& n = bvh.nodes[stack[--top]];
    F tnear;
    simd::Mask<A> lanes = node_overlap<A>(n, r, h.t, &tnear);
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
    const F& d = n.axis == 0 ? r.dx : (n.axis == 1 ? r.dy : r.dz);
    bool left_first = !std::signbit(d.get(lane));
    stack[top++] = left_first ? n.index + 1 : n.index;
    stack[top++] = left_first ? n.index : n.index + 1;
  }
}

}  // namespace raylane
