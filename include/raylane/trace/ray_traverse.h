// Single-ray traversal of the 8-wide BVH: one ray against the eight child boxes of a node in
// one SIMD step, the children it overlaps visited nearest first, and a leaf's rows tested
// several at a time (rows in lanes, simd/packet.h). For incoherent rays, where packets
// keep few lanes busy (bench/README.md: 21 % on diffuse rays), one ray per traversal wastes
// less (Wald et al. 2008, "Getting Rid of Packets"; Fuetterling et al. 2017). Included only
// by the per-ISA translation units.
#pragma once

#include <cfloat>
#include <cmath>
#include <type_traits>

#include "raylane/bvh/bvh.h"
#include "raylane/core/float_util.h"
#include "raylane/prims/prim_packets.h"
#include "raylane/scene/scene.h"
#include "raylane/simd/packet.h"
#include "raylane/trace/traversal_counters.h"

namespace raylane {

// The lanes a single ray uses: 8 (AVX2 registers) for AVX2 and AVX-512 — a node has eight
// children, and leaves hold a few rows — and 4 for SSE4.2, which takes a node in two halves.
template <class A>
using RayLanes = std::conditional_t<simd::kWidth<A> == 16, xsimd::fma3<xsimd::avx2>, A>;

// One ray, ready for node tests: origin, 1/d and which plane of each slab is near.
template <class N>
struct SingleRay {
  using F = simd::Floats<N>;
  F ox, oy, oz, inv_x, inv_y, inv_z, tmin;
  int near[3];  // 0: the near plane of axis k is the box's lo (d_k ≥ +0); 1: its hi
};

// Which of the children [first, first + W) of `n` the ray's segment (tmin, tfar) overlaps,
// as bits, and their entry distances. The same robust slab test as the packet path's
// node_overlap: NaN-keeping extrema (a NaN from 0·∞, a ray in a slab plane, leaves the
// segment's end), the far value widened by 2·γ3 (Ize 2013), once, for the smallest far value
// (the widening is monotone). The three axes are reduced as a tree, each against the
// NaN-free segment end first, to shorten the dependency chain.
template <class N>
inline uint32_t children_overlap(const WideNode& n, int first, const SingleRay<N>& r,
                                 const simd::Floats<N>& tfar, float* tnear) {
  using F = simd::Floats<N>;
  const F slack(float(2 * gamma_float(3)));
  auto near = [&](int k, const F& o, const F& inv) {
    return simd::max_keep<N>((F::load_aligned(&n.box[k][r.near[k]][first]) - o) * inv, r.tmin);
  };
  auto far = [&](int k, const F& o, const F& inv) {
    return simd::min_keep<N>((F::load_aligned(&n.box[k][1 - r.near[k]][first]) - o) * inv, tfar);
  };
  F t0 = xsimd::max(xsimd::max(near(0, r.ox, r.inv_x), near(1, r.oy, r.inv_y)),
                    near(2, r.oz, r.inv_z));
  F t1 =
      xsimd::min(xsimd::min(far(0, r.ox, r.inv_x), far(1, r.oy, r.inv_y)), far(2, r.oz, r.inv_z));
  // The segment's end is not widened (min with tfar again), so an unused slot (t0 = +inf)
  // never passes, even when tfar is FLT_MAX; a far of −inf widens to NaN, which keeps tfar.
  t1 = simd::min_keep<N>(simd::fma<N>(xsimd::abs(t1), slack, t1), tfar);
  t0.store_unaligned(tnear);
  return simd::bits<N>(t0 <= t1);
}

// A child waiting on the stack: a wide node (count 0) or a leaf's refs, and where the ray
// enters its box (skipped when a closer hit has been found meanwhile).
struct WideEntry {
  uint32_t child;
  uint16_t count;
  bool one_kind;  // a leaf whose child is the PrimRef of its first row (WideNode::child)
  float tnear;
};

inline WideEntry entry(const WideNode& n, int k, float tnear) {
  return {n.child[k], n.count[k], n.is_one_kind(k), tnear};
}

// Pushes the overlapped children of `n` (bits of `hit`) farthest first, so the nearest is on
// top. Sorting by entry distance is what makes closest-hit traversal cut early.
inline void push_nearest_last(const WideNode& n, uint32_t hit, const float* tnear, WideEntry* stack,
                              int& top) {
  int first = top;
  for (; hit; hit &= hit - 1) {
    int k = __builtin_ctz(hit);
    WideEntry e = entry(n, k, tnear[k]);
    int j = top++;
    for (; j > first && stack[j - 1].tnear < e.tnear; --j)  // insertion sort, descending
      stack[j] = stack[j - 1];
    stack[j] = e;
  }
}

// Occlusion needs any hit, not the nearest: the overlapped children go on the stack unsorted.
inline void push_any_order(const WideNode& n, uint32_t hit, const float* tnear, WideEntry* stack,
                           int& top) {
  for (; hit; hit &= hit - 1) {
    int k = __builtin_ctz(hit);
    stack[top++] = entry(n, k, tnear[k]);
  }
}

// Tests `count` rows of one kind from `head` on, with the ray in every lane and rows across.
template <class L>
inline void intersect_run_rows(const Scene& scene, PrimRef head, uint32_t count,
                               const RayPacket<L>& r, HitPacket<L>& h) {
  dispatch(head.tag(), [&](auto kind) {
    using Kind = decltype(kind);
    const auto& table = scene.table<Kind>();
    intersect_packet<L>(table, LanesAreRows<L>{head.row(), head.row() + count, table.size()}, r, h);
  });
}

// Calls f(head, rows) for each run of one kind of a wide node's leaf child: its one run, or
// the runs of its refs.
template <class F>
inline void for_each_leaf_run(const Bvh& bvh, const WideEntry& leaf, F&& f) {
  if (leaf.one_kind) return f(PrimRef::from_bits(leaf.child), uint32_t(leaf.count));
  for_each_ref_run(bvh, leaf.child, uint32_t(leaf.count), f);
}

// Tests the rows of one leaf: one run, or runs of one kind each found through the refs.
template <class L>
inline void intersect_leaf_rows(const Scene& scene, const Bvh& bvh, const WideEntry& leaf,
                                const RayPacket<L>& r, HitPacket<L>& h) {
  for_each_leaf_run(bvh, leaf, [&](PrimRef head, uint32_t rows) {
    intersect_run_rows<L>(scene, head, rows, r, h);
  });
}

// The closest hit among the lanes of h (each lane holds the closest of the rows it tested),
// made the answer of every lane so that later rows must beat it.
template <class L>
inline float settle_closest(HitPacket<L>& h) {
  constexpr int W = simd::kWidth<L>;
  alignas(64) float t[W];
  alignas(64) int32_t prim[W];
  simd::store<L>(t, h.t);
  simd::store<L>(prim, h.prim);
  int best = 0;
  for (int k = 1; k < W; ++k)
    if (t[k] < t[best]) best = k;
  h.t = simd::Floats<L>(t[best]);
  h.prim = simd::Ints<L>(prim[best]);
  return t[best];
}

// Closest hit (kAnyHit = false) or occlusion of one valid ray in the subtree below wide node
// `root` (0: the whole tree); h starts with t = tmax in every lane and returns the answer in
// every lane for closest hit, in some lane for occlusion. kCount: the instrumented copy.
template <class A, bool kAnyHit, bool kCount = false>
inline void traverse_ray(const Scene& scene, const Bvh& bvh, const RayPacket<RayLanes<A>>& r,
                         HitPacket<RayLanes<A>>& h, TraversalCounters* c = nullptr,
                         uint32_t root = 0) {
  using L = RayLanes<A>;
  using F = simd::Floats<L>;
  constexpr int W = simd::kWidth<L>;
  const SingleRay<L> ray{r.ox,
                         r.oy,
                         r.oz,
                         r.inv_dx,
                         r.inv_dy,
                         r.inv_dz,
                         r.tmin,
                         {int(r.sides.near_hi[0]), int(r.sides.near_hi[1]),
                          int(r.sides.near_hi[2])}};  // one ray: its lanes agree
  const std::vector<WideNode>& nodes = bvh.wide.nodes;
  // Boxes are tested against (tmin, min(tmax, FLT_MAX)): an unused slot (lo = +inf) is
  // entered at t = +inf, so it never passes, and nothing is lost — a hit beyond FLT_MAX
  // would round to +inf, which is not < tmax.
  float tfar = std::min(h.t.get(0), FLT_MAX);
  WideEntry stack[kWideStackSize];
  int top = 0;
  WideEntry cur{root, 0, false, 0.0f};
  for (;;) {
    if (cur.count == 0) {
      const WideNode& n = nodes[cur.child];
      alignas(32) float tnear[kWideArity];
      uint32_t hit = 0;
      for (int first = 0; first < kWideArity; first += W)
        hit |= children_overlap<L>(n, first, ray, F(tfar), tnear + first) << first;
      if constexpr (kCount) {
        ++c->node_tests;
        c->lanes_active += kWideArity;
        c->lanes_overlap += uint64_t(__builtin_popcount(hit));
      }
      if (hit != 0 && (hit & (hit - 1)) == 0) {  // one child: no sorting, no stack
        int k = __builtin_ctz(hit);
        cur = entry(n, k, tnear[k]);
        continue;
      }
      if (hit != 0) {
        if constexpr (kAnyHit) {
          push_any_order(n, hit, tnear, stack, top);
        } else {
          push_nearest_last(n, hit, tnear, stack, top);
        }
        cur = stack[--top];
        continue;
      }
    } else {
      if constexpr (kCount) ++c->leaf_visits, c->prim_tests += cur.count;
      F before = h.t;
      intersect_leaf_rows<L>(scene, bvh, cur, r, h);
      if constexpr (kAnyHit) {
        if (simd::any<L>(h.found)) return;
      } else if (simd::any<L>(h.t < before)) {
        tfar = settle_closest<L>(h);
      }
    }
    do {  // the next entry the ray can still reach
      if (top == 0) return;
      cur = stack[--top];
    } while (cur.tnear > tfar);
  }
}

}  // namespace raylane
