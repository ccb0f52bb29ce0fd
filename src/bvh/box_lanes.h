// The builder's loops over its records (build_lanes.h) for a lane type A of four or eight
// floats; included only by the per-ISA units (bin_lanes_*.cpp). A box is held as [lo, −hi]
// (BinBox): both corners then grow by one min, and the doubled centroid and its negation come
// from one subtraction of the box and its halves swapped — [lo, −hi] − [−hi, lo] = [lo + hi,
// −hi − lo]. With eight lanes (AVX2, AVX-512) that is one register and one instruction each,
// where four lanes (SSE4.2) take two; binning a record then updates each axis's bin with one
// load, one min and one store (it was two of each). The float operations on each lane are the
// ones the four-lane loops did before [lo, −hi], so every ISA bins, splits and bounds alike.
#pragma once

#include <limits>

#include "bvh/build_prim.h"
#include "raylane/simd/lanes.h"

namespace raylane::bvh_build::lanes {

// A box (or a pair [c, −c] of centroids) as [lo, −hi] in the lanes of A.
template <class A, int W = simd::kWidth<A>>
struct BoxPair;

template <class A>
struct BoxPair<A, 8> {
  using F = simd::Floats<A>;
  F v;

  // 0 in lanes 0-3, −0 in lanes 4-7: XOR with it negates the high half.
  static F high_sign() {
    alignas(32) static constexpr float k[8] = {0, 0, 0, 0, -0.0f, -0.0f, -0.0f, -0.0f};
    return F::load_aligned(k);
  }
  static BoxPair record(const BuildPrim& p) {
    return {F::load_unaligned(reinterpret_cast<const float*>(&p)) ^ high_sign()};
  }
  static BoxPair load(const BinBox& b) { return {F::load_aligned(b.lo)}; }
  void store(BinBox& b) const { v.store_aligned(b.lo); }
  // x < acc ? x : acc per lane, x being this (simd::min_keep): a NaN never replaces acc.
  BoxPair min(const BoxPair& acc) const { return {simd::min_keep<A>(v, acc.v)}; }
  // [c, −c'] with c = lo + hi (a non-finite lane read as 0, see BuildPrim) and c' equal to c but
  // for the sign of a zero (−hi − lo is +0 where −(lo + hi) is −0), which only a centroid
  // bound's zero can show and make_grid cannot see (its extent's sign does not matter).
  BoxPair centroid() const {
    F c = v - simd::swap_halves<A>(v);
    return {
        simd::select(xsimd::abs(c) < F(std::numeric_limits<float>::infinity()), c, high_sign())};
  }
  // Lanes 0-3: the low corner (or c).
  const F& low() const { return v; }
};

template <class A>
struct BoxPair<A, 4> {
  using F = simd::Floats<A>;
  F lo, neg_hi;

  static F sign() { return F(-0.0f); }
  static BoxPair record(const BuildPrim& p) {
    return {F::load_aligned(p.lo), F::load_aligned(p.hi) ^ sign()};
  }
  static BoxPair load(const BinBox& b) {
    return {F::load_aligned(b.lo), F::load_aligned(b.neg_hi)};
  }
  void store(BinBox& b) const { lo.store_aligned(b.lo), neg_hi.store_aligned(b.neg_hi); }
  BoxPair min(const BoxPair& acc) const {
    return {simd::min_keep<A>(lo, acc.lo), simd::min_keep<A>(neg_hi, acc.neg_hi)};
  }
  // As BoxPair<A, 8>::centroid, lane for lane.
  BoxPair centroid() const {
    F c = lo - neg_hi, neg_c = neg_hi - lo;
    auto finite = xsimd::abs(c) < F(std::numeric_limits<float>::infinity());
    return {simd::select(finite, c, F(0.0f)), simd::select(finite, neg_c, sign())};
  }
  const F& low() const { return lo; }
};

// A NodeBounds' box as a BoxPair and back (once per loop, so through memory).
template <class A>
BoxPair<A> to_pair(const Box4& b) {
  BinBox t;
  for (int k = 0; k < 4; ++k)
    t.lo[k] = b.lo[k], t.neg_hi[k] = -b.hi[k];
  return BoxPair<A>::load(t);
}
template <class A>
void from_pair(const BoxPair<A>& p, Box4& b) {
  BinBox t;
  p.store(t);
  for (int k = 0; k < 4; ++k)
    b.lo[k] = t.lo[k], b.hi[k] = -t.neg_hi[k];
}

// Running bounds of boxes and centroids, in registers.
template <class A>
struct PairBounds {
  BoxPair<A> box, centroids;

  explicit PairBounds(const NodeBounds& b)
      : box(to_pair<A>(b.box)), centroids(to_pair<A>(b.centroids)) {}
  void add(const BoxPair<A>& b, const BoxPair<A>& c) {
    box = b.min(box), centroids = c.min(centroids);
  }
  void store(NodeBounds& b) const { from_pair(box, b.box), from_pair(centroids, b.centroids); }
};

// The bin of each low lane of a centroid: (c − lo)·scale clamped to [0, bins − 1] in float
// before the conversion (max_keep maps NaN to 0, min_keep keeps the clamp: simd/lanes.h).
template <class A>
struct Binner {
  using F = simd::Floats<A>;
  F lo, scale, top;

  explicit Binner(const BinGrid& g) : top(float(g.bins - 1)) {
    alignas(32) float l[8] = {}, s[8] = {};  // high lanes (if any): 0, so their bin is 0
    for (int k = 0; k < 4; ++k)
      l[k] = g.lo[k], s[k] = g.scale[k];
    lo = F::load_aligned(l), scale = F::load_aligned(s);
  }
  // The bins of c's low lanes, at idx[0..3] (idx has room for every lane).
  void bins(const BoxPair<A>& c, int32_t* idx) const {
    F x = (c.low() - lo) * scale;
    x = simd::min_keep<A>(simd::max_keep<A>(x, F(0.0f)), top);
    xsimd::batch_cast<int32_t>(x).store_aligned(idx);
  }
};

template <class A>
void bound_records(const BuildPrim* prims, uint32_t n, NodeBounds& bounds) {
  PairBounds<A> acc(bounds);
  for (uint32_t i = 0; i < n; ++i) {
    BoxPair<A> box = BoxPair<A>::record(prims[i]);
    acc.add(box, box.centroid());
  }
  acc.store(bounds);
}

// Adds one record to the bins of all three axes (inlined: a call per record cost a tenth of
// the binning in the profile, its constants reloaded each time).
template <class A>
[[gnu::always_inline]] inline void bin_one(const BuildPrim& p, const Binner<A>& grid,
                                           BinSet& bins) {
  alignas(32) int32_t idx[8];
  BoxPair<A> box = BoxPair<A>::record(p);
  grid.bins(box.centroid(), idx);
  for (int a = 0; a < 3; ++a) {
    BinBox& b = bins.box[a][idx[a]];
    box.min(BoxPair<A>::load(b)).store(b);
    bins.cost[a][idx[a]] += p.cost;
  }
}

// Below this many records one set of bins is used; above it, two.
inline constexpr uint32_t kTwoSetsFrom = 256;

// Neighbouring records usually fall in the same bins, and each update of a bin waits for the
// previous one's store; above kTwoSetsFrom records, even and odd records go to two sets of
// bins, merged at the end, so two chains of updates overlap.
template <class A>
void bin_records(const BuildPrim* prims, uint32_t n, const BinGrid& grid, BinSet& bins) {
  const Binner<A> g(grid);
  if (n < kTwoSetsFrom) {
    for (uint32_t i = 0; i < n; ++i)
      bin_one(prims[i], g, bins);
    return;
  }
  BinSet odd;
  odd.clear(grid.bins);
  uint32_t i = 0;
  for (; i + 1 < n; i += 2) {
    bin_one(prims[i], g, bins);
    bin_one(prims[i + 1], g, odd);
  }
  if (i < n) bin_one(prims[i], g, bins);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < grid.bins; ++b) {
      BoxPair<A>::load(odd.box[a][b]).min(BoxPair<A>::load(bins.box[a][b])).store(bins.box[a][b]);
      bins.cost[a][b] += odd.cost[a][b];
    }
}

// Hoare's scheme: each record is classified once (the record met last may be twice, which
// adds its box to its side again: a min is idempotent); misplaced pairs are swapped. Each
// side's bounds are added in the branch that classified it, so they stay in registers.
template <class A>
uint32_t partition_records(BuildPrim* prims, uint32_t n, const BinGrid& grid, int axis,
                           int last_left_bin, NodeBounds& left, NodeBounds& right) {
  const Binner<A> g(grid);
  PairBounds<A> l(left), r(right);
  alignas(32) int32_t idx[8];
  auto goes_left = [&](uint32_t i) {
    BoxPair<A> box = BoxPair<A>::record(prims[i]), c = box.centroid();
    g.bins(c, idx);
    if (idx[axis] <= last_left_bin) {
      l.add(box, c);
      return true;
    }
    r.add(box, c);
    return false;
  };
  uint32_t i = 0, j = n;
  while (true) {
    while (i < j && goes_left(i))
      ++i;
    while (i < j && !goes_left(j - 1))
      --j;
    if (i >= j) break;
    std::swap(prims[i], prims[j - 1]);
    ++i, --j;
  }
  l.store(left), r.store(right);
  return i;
}

}  // namespace raylane::bvh_build::lanes
