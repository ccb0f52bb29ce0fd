// CSG blocks: the SIMD kernel (csg.h has the table and the reference). Lane code: included only
// through prims/prim_packets.h by the SIMD tracer's per-ISA translation units.
//
// Rays in lanes, one block at a time: each leaf's interval per lane (the float operations of its
// own kind's kernel), then Roth's classification (Roth 1982, "Ray casting for modeling solids")
// swept over the events in lanes: each step takes every lane's next leaf end beyond where it
// stands, classifies the points just after it by the block's program — one mask per leaf, the
// program's operators as mask operations — and stops the lanes where that differs from the
// classification just after tmin (until the first boundary, the points just before an end are
// classified so). A lane steps at most twice per leaf; nothing is allocated.
#pragma once

#include "raylane/prims/csg_leaf_lanes.h"
#include "raylane/prims/prim_list.h"
#include "raylane/simd/packet.h"

namespace raylane {

namespace detail {

// Lanes where exactly one of a and b holds. Spelled out: xsimd 8.1's `^` of two AVX-512 masks
// and `!=` of two SSE masks both compute their OR (as box_packet.h notes).
template <class A>
inline simd::Mask<A> csg_differ(const simd::Mask<A>& a, const simd::Mask<A>& b) {
  return (a & !b) | (b & !a);
}

// The program's classification of the points just after t (`after`) or just before it, each
// leaf's membership from its closed interval [t0, t1]; leaf `toggled` (or none: kCsgMaxLeaves)
// is taken from the other side.
template <class A>
simd::Mask<A> csg_classify_lanes(std::span<const uint32_t> program, const simd::Floats<A>* t0,
                                 const simd::Floats<A>* t1, const simd::Floats<A>& t, bool after,
                                 uint32_t toggled) {
  simd::Mask<A> stack[kCsgMaxLeaves];
  int top = 0;
  for (uint32_t code : program) {
    if (code < kCsgMaxLeaves) {
      bool side = after != (code == toggled);
      stack[top++] = side ? (t0[code] <= t) & (t < t1[code]) : (t0[code] < t) & (t <= t1[code]);
      continue;
    }
    simd::Mask<A> b = stack[--top], a = stack[top - 1];
    stack[top - 1] = code == kCsgUnion ? (a | b) : code == kCsgIntersect ? (a & b) : (a & !b);
  }
  return stack[0];
}

// The leaf seen where the lanes of `at_boundary` cross the boundary at t, as the reference
// chooses it (csg.cpp, leaf_at): the first leaf whose crossing alone changes the
// classification, else the first with an end at t. Where one leaf alone has an end at t (all
// but coincident faces), it is that leaf, with no classification.
template <class A>
simd::Ints<A> csg_leaf_at(std::span<const uint32_t> program, const simd::Floats<A>* t0,
                          const simd::Floats<A>* t1, uint32_t n, const simd::Floats<A>& t,
                          const simd::Mask<A>& at_boundary, const simd::Mask<A>& before) {
  using I = simd::Ints<A>;
  I leaf(0), first(0);
  const simd::Mask<A> none = at_boundary & !at_boundary;
  simd::Mask<A> has_first = none, twice = none, chosen = none;
  auto ends_at = [&](uint32_t i) { return at_boundary & ((t0[i] == t) | (t1[i] == t)); };
  for (uint32_t i = 0; i < n; ++i) {
    simd::Mask<A> ends = ends_at(i);
    twice = twice | (ends & has_first);
    first = simd::select<A>(ends & !has_first, I(int32_t(i)), first);
    has_first = has_first | ends;
  }
  if (simd::none<A>(twice)) return first;
  for (uint32_t i = 0; i < n; ++i) {
    simd::Mask<A> ends = ends_at(i);
    if (simd::none<A>(ends)) continue;
    simd::Mask<A> alone = csg_classify_lanes<A>(program, t0, t1, t, false, i);
    simd::Mask<A> pick = ends & !chosen & csg_differ<A>(alone, before);
    leaf = simd::select<A>(pick, I(int32_t(i)), leaf);
    chosen = chosen | pick;
  }
  return simd::select<A>(chosen, leaf, first);
}

// One block against the lanes of `lanes`: commits the first boundary beyond tmin nearer than
// each lane's closest hit so far, naming the leaf seen there.
template <class A>
inline void csg_block_lanes(const CsgTable& c, uint32_t block, const simd::Mask<A>& lanes,
                            const RayPacket<A>& r, HitPacket<A>& h) {
  using F = simd::Floats<A>;
  const F inf(std::numeric_limits<float>::infinity());
  const uint32_t n = c.leaf_count[block], first = c.leaf_begin[block];
  const std::span<const uint32_t> program = c.program_of(block);
  F t0[kCsgMaxLeaves], t1[kCsgMaxLeaves];
  for (uint32_t i = 0; i < n; ++i)
    csg_leaf_interval_lanes<A>(c, first + i, r, t0[i], t1[i]);
  simd::Mask<A> live = lanes;
  F at = r.tmin;
  const simd::Ints<A> base(prim_bits(tag_of<Csg>, first));
  // Until the first boundary the classification is the one just after tmin, so the first end
  // after which it differs from that one is the boundary: one classification per step.
  const simd::Mask<A> before = csg_classify_lanes<A>(program, t0, t1, at, true, kCsgMaxLeaves);
  for (uint32_t step = 0; step <= 2 * n; ++step) {
    F next = inf;  // each lane's first leaf end beyond `at`; ends that are NaN never are
    for (uint32_t i = 0; i < n; ++i) {
      next = simd::min_keep<A>(simd::select<A>(t0[i] > at, t0[i], inf), next);
      next = simd::min_keep<A>(simd::select<A>(t1[i] > at, t1[i], inf), next);
    }
    live = live & (next < h.t);
    if (simd::none<A>(live)) return;
    simd::Mask<A> after = csg_classify_lanes<A>(program, t0, t1, next, true, kCsgMaxLeaves);
    simd::Mask<A> boundary = live & csg_differ<A>(before, after);
    if (simd::any<A>(boundary)) {
      simd::Ints<A> leaf = csg_leaf_at<A>(program, t0, t1, n, next, boundary, before);
      commit_hit<A>(next, boundary, base + leaf, h);
      live = live & !boundary;
    }
    at = next;
  }
}

}  // namespace detail

// The packet kernel. Rays in lanes: one block per step, broadcast. One ray in every lane (the
// single-ray traversal): the blocks' programs differ, so each block of the run is tested with
// the ray in lane 0 alone, whose hit the traversal's lane reduction then finds.
template <class A, class Rows>
[[gnu::always_inline]] inline void intersect_packet(const CsgTable& c, Rows rows,
                                                    const RayPacket<A>& r, HitPacket<A>& h) {
  for (; rows.more(); rows.next()) {
    if constexpr (Rows::kOneRay) {
      const uint32_t end = std::min<uint32_t>(rows.end, rows.i + simd::kWidth<A>);
      for (uint32_t b = rows.i; b < end; ++b)
        detail::csg_block_lanes<A>(c, b, simd::first_lanes<A>(1), r, h);
    } else {
      detail::csg_block_lanes<A>(c, rows.i, rows.mask(), r, h);
    }
  }
}

}  // namespace raylane
