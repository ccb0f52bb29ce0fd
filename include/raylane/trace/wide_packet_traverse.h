// Packets of mixed directions over the 8-wide tree (Embree's hybrid traversal: Benthin et al.
// 2012, "Combining Single and Packet-Ray Tracing for Arbitrary Ray Distributions on the Intel
// MIC Architecture"): the packet's lanes are tested against a wide node's children one child
// at a time, all lanes of a child in one SIMD step, and once few lanes enter a node each of
// them finishes its subtree alone over the same tree (trace/ray_traverse.h). The binary walk
// it replaces took a step per binary node, each a node's load and a branch on the lanes
// entered, and handed lanes over only where a binary node roots a wide one (bench/README.md,
// "Packets of mixed directions over the 8-wide tree"). Closest hit only: coherent packets and
// occlusion keep the binary walk (trace/packet_traverse.h). Included only by the per-ISA
// translation units.
#pragma once

#include <limits>

#include "raylane/bvh/bvh.h"
#include "raylane/trace/packet_traverse.h"
#include "raylane/trace/ray_traverse.h"
#include "raylane/trace/single_ray.h"

namespace raylane {

// Which lanes of `lanes` overlap child slot k of `n`, and where they enter it: node_overlap's
// test on the slot's box (lanes of mixed sides, so the planes are selected per lane).
template <class A>
[[gnu::always_inline]] inline simd::Mask<A> child_overlap(const WideNode& n, int k,
                                                          const RayPacket<A>& r,
                                                          const simd::Mask<A>& lanes,
                                                          const simd::Floats<A>& tfar,
                                                          simd::Floats<A>& tnear) {
  auto plane = [&](int axis, bool hi) __attribute__((always_inline)) {
    return n.box[axis][hi][k];
  };
  return slab_overlap<A, false>(plane, r, tfar, tnear) & lanes;
}

// Tests `lanes` of the packet against the rows of a wide node's leaf child.
template <class A>
inline void intersect_wide_leaf(const Scene& scene, const Bvh& bvh, const WideEntry& leaf,
                                const RayPacket<A>& r, const simd::Mask<A>& lanes,
                                HitPacket<A>& h) {
  for_each_leaf_run(bvh, leaf, [&](PrimRef head, uint32_t rows) {
    intersect_run_lanes<A>(scene, head, rows, r, lanes, h);
  });
}

// The children of `n` that some of `lanes` enter, in `order` from farthest to nearest by the
// nearest entry among their lanes, with their lanes and entry distances in `child`; returns
// how many.
template <class A, bool kCount>
inline int entered_children(const WideNode& n, const RayPacket<A>& r, const simd::Mask<A>& lanes,
                            const simd::Floats<A>& tfar, ChildOverlap<A> (&child)[kWideArity],
                            int (&order)[kWideArity], TraversalCounters* c) {
  using F = simd::Floats<A>;
  uint32_t hit = 0;
  for (int k = 0; k < n.arity; ++k) {
    ChildOverlap<A>& o = child[k];
    o.lanes = child_overlap<A>(n, k, r, lanes, tfar, o.tnear);
    hit |= uint32_t(simd::any<A>(o.lanes)) << k;
    if constexpr (kCount) c->lanes_overlap += uint64_t(simd::popcount<A>(simd::bits<A>(o.lanes)));
  }
  if constexpr (kCount) {
    c->node_tests += n.arity;
    c->lanes_active += uint64_t(n.arity) * uint64_t(simd::popcount<A>(simd::bits<A>(lanes)));
  }
  if (hit == 0) return 0;
  if ((hit & (hit - 1)) == 0) {  // one child: no order to find
    order[0] = __builtin_ctz(hit);
    return 1;
  }
  const F never(std::numeric_limits<float>::infinity());
  float key[kWideArity];
  int entered = 0;
  for (; hit; hit &= hit - 1) {
    const int k = __builtin_ctz(hit);
    const ChildOverlap<A>& o = child[k];
    const float d = simd::reduce_min<A>(simd::select<A>(o.lanes, o.tnear, never));
    int j = entered++;
    for (; j > 0 && key[j - 1] < d; --j)  // insertion sort, descending
      key[j] = key[j - 1], order[j] = order[j - 1];
    key[j] = d, order[j] = k;
  }
  return entered;
}

// A packet whose lanes have spread out keeps few of them busy at each node, while one ray over
// the 8-wide tree tests eight boxes per step. So, as in Embree's hybrid (Benthin et al. 2012),
// once at most this many lanes enter a wide node, each of them finishes that subtree alone
// (trace/ray_traverse.h). The threshold is the best one measured per instruction set; coherent
// packets and occlusion do not hand over, as every threshold tried lost there (the figures:
// bench/README.md, "Packets of mixed directions over the 8-wide tree" and "Hybrid packets for
// incoherent rays").
template <class A>
inline constexpr int kSingleRayLanes = simd::kWidth<A> >= 16 ? simd::kWidth<A> / 8 : 1;

// The lanes of `lanes` find their closest hits in the subtree below wide node `wide_root` one
// at a time, each from its closest hit so far; their answers go back into h.
template <class A, bool kCount>
inline void lanes_as_single_rays(const Scene& scene, const Bvh& bvh, uint32_t wide_root,
                                 const RayPacket<A>& r, const simd::Mask<A>& lanes, HitPacket<A>& h,
                                 TraversalCounters* c) {
  using L = RayLanes<A>;
  using FL = simd::Floats<L>;
  using F = simd::Floats<A>;
  constexpr int W = simd::kWidth<A>;
  alignas(64) float col[11][W];
  const F* src[11] = {&r.ox,     &r.oy,     &r.oz,     &r.dx,   &r.dy,  &r.dz,
                      &r.inv_dx, &r.inv_dy, &r.inv_dz, &r.tmin, &r.time};
  for (int k = 0; k < 11; ++k)
    simd::store<A>(col[k], *src[k]);
  alignas(64) float t[W];
  alignas(64) int32_t prim[W];
  simd::store<A>(t, h.t);
  simd::store<A>(prim, h.prim);
  // Each lane's shear frame as the packet's set-up computed it (RayShear, per lane: the same
  // operations as scalar_shear's), so that a lane handed over does not divide again.
  alignas(64) float shear[3][W];
  simd::store<A>(shear[0], r.shear.sx), simd::store<A>(shear[1], r.shear.sy);
  simd::store<A>(shear[2], r.shear.sz);
  uint32_t z_is[2] = {simd::bits<A>(r.shear.z_is[0]), simd::bits<A>(r.shear.z_is[1])};
  uint32_t x_is[2] = {simd::bits<A>(r.shear.x_is[0]), simd::bits<A>(r.shear.x_is[1])};
  auto axis = [](const uint32_t* is, int k) {
    return (is[0] >> k) & 1u ? 0 : (is[1] >> k) & 1u ? 1 : 2;
  };
  TraversalCounters single;
  for (uint32_t m = simd::bits<A>(lanes); m; m &= m - 1) {
    int k = __builtin_ctz(m);
    RayScalars one{{col[0][k], col[1][k], col[2][k]},
                   {col[3][k], col[4][k], col[5][k]},
                   {col[6][k], col[7][k], col[8][k]},
                   col[9][k],
                   t[k],
                   col[10][k]};
    const int kz = axis(z_is, k), kx = axis(x_is, k);
    const ShearScalars frame{shear[0][k], shear[1][k], shear[2][k], kx, 3 - kx - kz, kz};
    RayPacket<L> ray = broadcast_ray<L>(one, &frame);
    HitPacket<L> hit{FL(t[k]), simd::Ints<L>(prim[k]), FL(0.0f) != FL(0.0f)};
    traverse_ray<A, false, kCount>(scene, bvh, ray, hit, &single, wide_root);
    if (simd::none<L>(hit.found)) continue;
    t[k] = settle_closest<L>(hit);
    prim[k] = hit.prim.get(0);
  }
  F t_new = simd::load<A>(t);
  h.found = h.found | (t_new < h.t);
  h.t = t_new;
  h.prim = simd::load<A>(prim);
  if constexpr (kCount) {
    c->single_rays += uint64_t(__builtin_popcount(simd::bits<A>(lanes)));
    c->single_node_tests += single.node_tests;
    c->single_prim_tests += single.prim_tests;
  }
}

// Closest hit for a packet of mixed directions (h.t starts at tmax), over bvh.wide.
template <class A, bool kCount>
inline void traverse_wide_packet(const Scene& scene, const Bvh& bvh, const RayPacket<A>& r,
                                 HitPacket<A>& h, TraversalCounters* c) {
  const std::vector<WideNode>& nodes = bvh.wide.nodes;
  // A child waiting with the lanes that entered it and where (its WideEntry::tnear is unused).
  PacketEntry<A, WideEntry> stack[kWideStackSize];
  int top = 0;
  WideEntry cur{0, 0, false, 0.0f};
  simd::Mask<A> lanes = r.active;
  for (;;) {
    if (cur.count > 0) {
      if constexpr (kCount) ++c->leaf_visits, c->prim_tests += cur.count;
      intersect_wide_leaf<A>(scene, bvh, cur, r, lanes, h);
    } else if (simd::popcount<A>(simd::bits<A>(lanes)) <= kSingleRayLanes<A>) {
      lanes_as_single_rays<A, kCount>(scene, bvh, cur.child, r, lanes, h, c);
    } else {
      const WideNode& n = nodes[cur.child];
      ChildOverlap<A> child[kWideArity];
      int order[kWideArity];
      const int entered = entered_children<A, kCount>(n, r, lanes, h.t, child, order, c);
      if (entered > 0) {
        for (int i = 0; i + 1 < entered; ++i) {
          const int k = order[i];
          stack[top++] = {child[k].tnear, child[k].lanes, entry(n, k, 0.0f)};
        }
        const int k = order[entered - 1];
        cur = entry(n, k, 0.0f);
        lanes = child[k].lanes;
        continue;
      }
    }
    do {  // the next waiting child that some lane can still reach
      if (top == 0) return;
      const PacketEntry<A, WideEntry>& e = stack[--top];
      cur = e.node;
      lanes = e.lanes & (e.tnear <= widen_far<A>(h.t));
    } while (simd::none<A>(lanes));
  }
}

}  // namespace raylane
