// Packet traversal of the BVH: W rays in lanes visit a node together when any active lane's
// segment overlaps its box (docs/design.md, "Packets"). Included only by the per-ISA translation
// units, which instantiate it for their instruction set.
#pragma once

#include "raylane/bvh/bvh.h"
#include "raylane/core/float_util.h"
#include "raylane/prims/prim_packets.h"
#include "raylane/scene/scene.h"
#include "raylane/simd/packet.h"
#include "raylane/trace/traversal_counters.h"

namespace raylane {

// x + 2·γ3·|x|: a far distance widened by its rounding error (Ize 2013, "Robust BVH Ray
// Traversal"; pbrt-v4 Bounds3::IntersectP). Monotone in x.
template <class A>
inline simd::Floats<A> widen_far(const simd::Floats<A>& x) {
  return simd::fma<A>(xsimd::abs(x), simd::Floats<A>(float(2 * gamma_float(3))), x);
}

// Which lanes' segments (tmin, tfar) overlap a node box, and where each enters it. Closed
// box, NaN-keeping extrema (a ray lying in a slab plane keeps the accumulator: docs/hard-cases.md
// B4), near and far planes chosen by the sign of 1/d, which is the sign of d even for ±0 (B3): one
// choice per axis when the lanes agree on it (kSameSides, RayPacket::sides), per lane otherwise.
// Each t carries three roundings (difference, reciprocal, product); the far end is widened by 2·γ3
// of its size so that rounding never closes an overlap. The widening is monotone, so it is applied
// once, to the smallest far value, instead of to each: that widens tfar too, which can only add a
// visit. A far value of −inf (a ray parallel to a slab and outside it, or an exit that overflows
// behind the origin) widens to NaN and the box is rejected, rightly: the ray cannot be inside it.
//
// `plane(k, hi)` gives the box's hi (hi = 1) or lo (0) plane on axis k: a binary node's box, or
// one child slot of a wide node (trace/wide_packet_traverse.h), tested by the same arithmetic.
template <class A, bool kSameSides, class Planes>
[[gnu::always_inline]] inline simd::Mask<A> slab_overlap(const Planes& plane, const RayPacket<A>& r,
                                                         const simd::Floats<A>& tfar,
                                                         simd::Floats<A>& tnear) {
  using F = simd::Floats<A>;
  const SlabSides<A>& sides = r.sides;
  F t0 = r.tmin, t1 = tfar;
  // Inlined by force: GCC 12 called this lambda out of line once `plane` was a parameter, its
  // accumulators through memory, and primary rays lost much of their speed (bench/README.md,
  // "Packets of mixed directions over the 8-wide tree").
  auto axis = [&](int k, const F& o, const F& inv) __attribute__((always_inline)) {
    F near, far;
    if constexpr (kSameSides) {
      bool hi = sides.near_hi[k];
      near = F(plane(k, hi)), far = F(plane(k, !hi));
    } else {
      near = simd::select<A>(sides.hi_first[k], F(plane(k, 1)), F(plane(k, 0)));
      far = simd::select<A>(sides.hi_first[k], F(plane(k, 0)), F(plane(k, 1)));
    }
    t0 = simd::max_keep<A>((near - o) * inv, t0);
    t1 = simd::min_keep<A>((far - o) * inv, t1);
  };
  axis(0, r.ox, r.inv_dx);
  axis(1, r.oy, r.inv_dy);
  axis(2, r.oz, r.inv_dz);
  t1 = widen_far<A>(t1);
  tnear = t0;
  return (t0 <= t1) & r.active;
}

template <class A, bool kSameSides>
[[gnu::always_inline]] inline simd::Mask<A> node_overlap(const BvhNode& n, const RayPacket<A>& r,
                                                         const simd::Floats<A>& tfar,
                                                         simd::Floats<A>& tnear) {
  auto plane = [&](int k, bool hi) __attribute__((always_inline)) {
    return hi ? n.hi[k] : n.lo[k];
  };
  return slab_overlap<A, kSameSides>(plane, r, tfar, tnear);
}

// Tests `lanes` of the packet against rows head.row() … head.row() + rows − 1 of head's kind.
// kLeaveAims (occlusion): a run of one primitive whose hits name it is not tested in the lanes
// aimed at it. Its hit cannot block them (RayStream::aim), and a shadow ray ends at the point
// it aims at, so it meets that primitive at its far end: in a scene lit by one sphere, every
// unblocked shadow ray tested its light only to be let through (the saving: bench/README.md,
// "The surfaces' rows read in place, ..."). Not testing it also leaves the lane's segment
// whole where the hit would have shortened it, which the aim's contract allows (something past
// the aim's hit may block). A longer run, or a CSG or SDF block (whose hits name its leaves,
// one of which may block another), tests every lane; traverse_packet_loop lets the aim's hit
// through after the leaf.
template <class A, bool kLeaveAims = false>
inline void intersect_run_lanes(const Scene& scene, PrimRef head, uint32_t rows,
                                const RayPacket<A>& r, const simd::Mask<A>& lanes,
                                HitPacket<A>& h) {
  simd::Mask<A> test = lanes;
  if constexpr (kLeaveAims) {  // decided before the kinds' dispatch, a call
    if (rows == 1) {
      const simd::Mask<A> aimed = simd::equal<A>(r.aim, simd::Ints<A>(int32_t(head.bits())));
      if (simd::any<A>(aimed & lanes) && kind_hits_name_their_row(head.tag())) {
        test = lanes & !aimed;
        if (simd::none<A>(test)) return;
      }
    }
  }
  dispatch(head.tag(), [&](auto kind) {
    using Kind = decltype(kind);
    intersect_packet<A>(scene.table<Kind>(), LanesAreRays<A>{head.row(), head.row() + rows, test},
                        r, h);
  });
}

// Tests `lanes` of the packet against the rows of one leaf: runs of one kind, whose rows are
// contiguous because the tables were permuted into leaf order.
template <class A, bool kLeaveAims = false>
inline void intersect_leaf(const Scene& scene, const Bvh& bvh, const BvhNode& leaf,
                           const RayPacket<A>& r, const simd::Mask<A>& lanes, HitPacket<A>& h) {
  for_each_run(bvh, leaf, [&](PrimRef head, uint32_t rows) {
    intersect_run_lanes<A, kLeaveAims>(scene, head, rows, r, lanes, h);
  });
}

// A node waiting on the traversal stack: its box was found overlapped by `lanes`, entered at
// `tnear`. When it is popped, the lanes whose closest hit has since come nearer than tnear
// drop out — the same answer as testing the box again (the widening is monotone, so
// t0 ≤ widen(min(far, t)) is t0 ≤ widen(far) and t0 ≤ widen(t)).
// `Node`: a binary node's index, or a wide node's child (trace/wide_packet_traverse.h).
template <class A, class Node = uint32_t>
struct PacketEntry {
  simd::Floats<A> tnear;
  simd::Mask<A> lanes;
  Node node;
};

// A child as one packet test saw it: the lanes that overlap its box, and where they enter.
template <class A>
struct ChildOverlap {
  simd::Mask<A> lanes;
  simd::Floats<A> tnear;
};

// Whether the left child of `n` is the nearer one when the packet overlaps both. A coherent
// packet (kSameSides) goes by the direction of its first overlapping lane along the split
// axis, which costs nothing and speaks for every lane. In a mixed packet one lane speaks for
// few others, so the child that most of the lanes entering both enter first is the nearer
// (1 thread, AVX-512, median of 3: diffuse rays 1.16-1.34x, coherent sets unchanged).
template <class A, bool kSameSides>
inline bool left_child_nearer(const BvhNode& n, const RayPacket<A>& r, const simd::Mask<A>& lanes,
                              const ChildOverlap<A>& left, const ChildOverlap<A>& right) {
  if constexpr (kSameSides) {
    uint32_t lane = uint32_t(__builtin_ctz(simd::bits<A>(lanes)));
    return !((r.sides.hi_first_bits[n.axis] >> lane) & 1u);
  } else {
    uint32_t both = simd::bits<A>(left.lanes & right.lanes);
    uint32_t left_nearer = simd::bits<A>(left.tnear <= right.tnear) & both;
    return 2 * __builtin_popcount(left_nearer) >= __builtin_popcount(both);
  }
}

// Which child of `n` a packet that overlaps both visits first: closest hit goes nearest first,
// so that a hit found there culls the farther child. Occlusion goes farthest first. Every order
// gives an occlusion ray the same answer — whether any primitive lies in (tmin, tmax), found
// by the same kernels — so the order only decides how soon a blocker is found, and front to
// back is not the best order for occlusion rays (Ize and Hansen 2011, "RTSAH Traversal Order
// for Occlusion Rays"). Shadow rays start on a surface: every box around their origin is
// entered, and its rows tested, yet the surface they leave almost never blocks them, while a
// blocker anywhere along the segment is found just as well from the light's end (triangles
// are two-sided, and a closed solid is hit where the ray leaves it). It pays on every mesh and
// costs a little where shadow rays end on a light sphere, the farthest box along every segment
// (the figures: bench/README.md, "Embree's robust mode, occlusion packets far child first").
template <class A, bool kAnyHit, bool kSameSides>
inline bool left_child_first(const BvhNode& n, const RayPacket<A>& r, const simd::Mask<A>& lanes,
                             const ChildOverlap<A>& left, const ChildOverlap<A>& right) {
  return left_child_nearer<A, kSameSides>(n, r, lanes, left, right) != kAnyHit;
}

// Closest hit (kAnyHit = false) or occlusion (true) for one packet; h.t starts at tmax.
// kCount = true is the instrumented copy used by the benchmark; `c` is unused otherwise.
// kSameSides: every active lane meets each slab from the same side (RayPacket::sides), so
// the node test loads planes instead of selecting them per lane: a second instantiation of
// the loop, as for any-hit, because the choice holds for the whole packet. An inner
// node's two children (adjacent, one cache line) are tested together, so the two box tests
// overlap in the pipeline; the nearer one is visited, the other pushed.
template <class A, bool kAnyHit, bool kCount, bool kSameSides>
inline void traverse_packet_loop(const Scene& scene, const Bvh& bvh, RayPacket<A>& r,
                                 HitPacket<A>& h, TraversalCounters* c) {
  using F = simd::Floats<A>;
  auto test = [&](const BvhNode& n, F& tnear) {
    simd::Mask<A> lanes = node_overlap<A, kSameSides>(n, r, h.t, tnear);
    if constexpr (kCount) {
      ++c->node_tests;
      c->lanes_active += uint64_t(__builtin_popcount(simd::bits<A>(r.active)));
      c->lanes_overlap += uint64_t(__builtin_popcount(simd::bits<A>(lanes)));
    }
    return lanes;
  };
  PacketEntry<A> stack[kBvhStackSize];
  int top = 0;
  F tnear;
  uint32_t cur = 0;
  simd::Mask<A> lanes = test(bvh.nodes[0], tnear);
  if (simd::none<A>(lanes)) return;
  for (;;) {
    const BvhNode& n = bvh.nodes[cur];
    if (n.is_leaf()) {
      if constexpr (kCount) ++c->leaf_visits, c->prim_tests += n.count;
      intersect_leaf<A, kAnyHit>(scene, bvh, n, r, lanes, h);
      if constexpr (kAnyHit) {
        // A lane whose closest hit so far is the primitive it is aimed at has not found a
        // blocker: the kernel shortened its segment to that hit, and it goes on looking
        // before it. (A blocker found first retires the lane at once.)
        h.found = h.found & !simd::equal<A>(h.prim, r.aim);
        r.active = r.active & !h.found;
        if (simd::none<A>(r.active)) return;
      }
    } else {
      F t_left, t_right;
      simd::Mask<A> left = test(bvh.nodes[n.index], t_left);
      simd::Mask<A> right = test(bvh.nodes[n.index + 1], t_right);
      bool go_left = simd::any<A>(left), go_right = simd::any<A>(right);
      if (go_left && go_right) {
        bool left_first =
            left_child_first<A, kAnyHit, kSameSides>(n, r, lanes, {left, t_left}, {right, t_right});
        stack[top++] = left_first ? PacketEntry<A>{t_right, right, n.index + 1}
                                  : PacketEntry<A>{t_left, left, n.index};
        cur = left_first ? n.index : n.index + 1;
        lanes = left_first ? left : right;
        continue;
      }
      if (go_left || go_right) {
        cur = go_left ? n.index : n.index + 1;
        lanes = go_left ? left : right;
        continue;
      }
    }
    do {  // the next waiting node that some lane can still reach
      if (top == 0) return;
      const PacketEntry<A>& e = stack[--top];
      cur = e.node;
      lanes = e.lanes & r.active & (e.tnear <= widen_far<A>(h.t));
    } while (simd::none<A>(lanes));
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
