// The SAH sweep over a node's bins (sah_split.h) in double lanes, for one instruction set A;
// included only by the builder's per-ISA units (bin_lanes_*.cpp). The scalar sweep did 2 × 3
// × bins steps of six min/max, six conversions and an area each, one axis and one direction
// at a time (28-36 % of the sphereflake's and the bunny's builds). Here the three axes are
// lanes 0-2 of a row of four doubles, and the sweeps from the left and from the right run at
// once, lanes 0-3 and 4-7 of an eight-double pack (one AVX-512 register, two AVX2, four
// SSE4.2): one step adds bin k on the left and bin bins − 1 − k on the right. Every value is
// computed as the scalar sweep computed it — the same double operations in the same order,
// without contraction into FMA (CMakeLists.txt) — so the choice and its cost are the same to
// the bit (SahSplit.EveryIsaSweepEqualsTheDirectCosts).
#pragma once

#include <cfloat>

#include "bvh/box_lanes.h"
#include "bvh/sah_split.h"
#include "raylane/simd/lane_convert.h"
#include "raylane/simd/lanes.h"

namespace raylane::bvh_build::lanes {

// Bin b of every axis, transposed so that lane a is axis a: lo[k][a] is coordinate k of the
// low corner of bin b's box on axis a; tests[a] its summed test cost.
struct alignas(32) BinRow {
  double lo[3][4], hi[3][4], tests[4];
};

// Eight double lanes as registers of A: lanes 0-3 come from one row of four, 4-7 from another.
template <class A>
struct Pack {
  using D = simd::Doubles<A>;
  static constexpr int kWidth = simd::kDoubleWidth<A>;
  static constexpr int kRegs = 8 / kWidth;
  D r[kRegs];

  void store(double* left, double* right) const {
    for (int j = 0; j < kRegs; ++j)
      simd::store_pack<A>(left, right, j, r[j]);
  }
};

// One direction's growing box and summed cost per lane.
template <class A>
struct SweepLanes {
  using D = simd::Doubles<A>;
  using P = Pack<A>;
  P lo[3], hi[3], tests;

  SweepLanes() {
    for (int j = 0; j < P::kRegs; ++j) {
      for (int k = 0; k < 3; ++k)
        lo[k].r[j] = D(HUGE_VAL), hi[k].r[j] = D(-HUGE_VAL);
      tests.r[j] = D(0.0);
    }
  }

  // Adds the bins of `left` (lanes 0-3) and `right` (lanes 4-7); returns area × summed cost,
  // the area as Sweep::half_area computes it: 0 for an empty box, at most DBL_MAX.
  P add(const BinRow& left, const BinRow& right) {
    P out;
    for (int j = 0; j < P::kRegs; ++j) {
      D d[3];
      for (int k = 0; k < 3; ++k) {
        D l = simd::load_pack<A>(left.lo[k], right.lo[k], j);
        D h = simd::load_pack<A>(left.hi[k], right.hi[k], j);
        lo[k].r[j] = xsimd::min(lo[k].r[j], l);
        hi[k].r[j] = xsimd::max(hi[k].r[j], h);
        d[k] = hi[k].r[j] - lo[k].r[j];
      }
      tests.r[j] = tests.r[j] + simd::load_pack<A>(left.tests, right.tests, j);
      D area = d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
      area = xsimd::select(area <= D(DBL_MAX), area, D(DBL_MAX));
      auto filled = d[0] >= D(0.0) && d[1] >= D(0.0) && d[2] >= D(0.0);
      out.r[j] = xsimd::select(filled, area, D(0.0)) * tests.r[j];
    }
    return out;
  }
};

// Fills rows[0, n) from the bins: the transposition the lanes need. The boxes of the three
// axes and a row of +inf are four rows of [lo | −hi] that one 4 × 4 transposition per half
// turns into [lo_k of each axis | −hi_k of each axis] for k = 0, 1, 2 (B: four or eight float
// lanes, box_lanes.h); −hi is negated back and widened to double, both exactly. The +inf row
// pads lane 3 with lo = +inf and hi = −inf, an empty box.
template <class B>
void transpose_bins(const BinSet& bins, int n, BinRow* rows) {
  using F = simd::Floats<B>;
  using P = BoxPair<B>;
  const F inf(HUGE_VALF);
  for (int b = 0; b < n; ++b) {
    BinRow& row = rows[b];
    P box[3] = {P::load(bins.box[0][b]), P::load(bins.box[1][b]), P::load(bins.box[2][b])};
    if constexpr (simd::kWidth<B> == 8) {
      F r[4] = {box[0].v, box[1].v, box[2].v, inf};
      simd::transpose4<B>(r[0], r[1], r[2], r[3]);
      for (int k = 0; k < 3; ++k)
        simd::store_widened<B>(row.lo[k], row.hi[k], r[k] ^ P::high_sign());
    } else {
      F lo[4] = {box[0].lo, box[1].lo, box[2].lo, inf};
      F hi[4] = {box[0].neg_hi, box[1].neg_hi, box[2].neg_hi, inf};
      simd::transpose4<B>(lo[0], lo[1], lo[2], lo[3]);
      simd::transpose4<B>(hi[0], hi[1], hi[2], hi[3]);
      for (int k = 0; k < 3; ++k) {
        simd::store_widened<B>(row.lo[k], nullptr, lo[k]);
        simd::store_widened<B>(row.hi[k], nullptr, hi[k] ^ P::sign());
      }
    }
    for (int a = 0; a < 3; ++a)
      row.tests[a] = double(bins.cost[a][b]) * kCostUnit;
    row.tests[3] = 0;
  }
}

// The first cheapest candidate over candidates [0, n − 1) of every axis whose `usable` lane is
// set, in the scalar order (axis by axis, bins from the left, strictly cheaper replaces): two
// candidates per pack (even in lanes 0-3, odd in 4-7), each lane keeping its first minimum,
// then the lanes compared with ties going to the lower bin, then to the lower axis.
template <class A>
Split choose(const double (*left)[4], const double (*right)[4], const double (*tl)[4],
             const double (*tr)[4], int candidates, const double (&usable)[4], double traversal,
             double parent_area) {
  using D = simd::Doubles<A>;
  using P = Pack<A>;
  alignas(64) double best_cost[8], best_bin[8];
  P cost_best, bin_best;
  for (int j = 0; j < P::kRegs; ++j)
    cost_best.r[j] = D(HUGE_VAL), bin_best.r[j] = D(-1.0);
  // An odd count of candidates: the last pack's odd half reads a row of zeros, never valid.
  static constexpr double kZeros[4] = {0, 0, 0, 0}, kOnes[4] = {1, 1, 1, 1};
  for (int c = 0; c < candidates; c += 2) {
    const bool pair = c + 1 < candidates;
    for (int j = 0; j < P::kRegs; ++j) {
      auto at = [&](const double(*rows)[4]) {
        return simd::load_pack<A>(rows[c], pair ? rows[c + 1] : kZeros, j);
      };
      D cost = D(traversal) + (at(left) + at(right)) / D(parent_area);
      D ok = simd::load_pack<A>(usable, usable, j);
      auto valid = at(tl) > D(0.0) && at(tr) > D(0.0) && ok > D(0.0);
      auto better = valid && cost < cost_best.r[j];
      cost_best.r[j] = xsimd::select(better, cost, cost_best.r[j]);
      D bin = simd::load_pack<A>(kZeros, kOnes, j) + D(double(c));
      bin_best.r[j] = xsimd::select(better, bin, bin_best.r[j]);
    }
  }
  cost_best.store(best_cost, best_cost + 4);
  bin_best.store(best_bin, best_bin + 4);
  Split best;
  for (int a = 0; a < 3; ++a)
    for (int half : {0, 4}) {
      double cost = best_cost[half + a];
      int bin = int(best_bin[half + a]);
      if (bin < 0) continue;
      bool earlier = best.axis == a && bin < best.last_left;
      if (cost < best.cost || (cost == best.cost && earlier)) best = {a, bin, cost};
    }
  return best;
}

// best_split (sah_split.h) for instruction set A (B: its lanes of the bins' boxes), given the
// parent's half area.
template <class A, class B>
Split sweep_bins(const BinSet& bins, const BinGrid& grid, double parent_area,
                 double traversal_cost) {
  const int n = grid.bins;
  BinRow rows[kMaxBins];
  transpose_bins<B>(bins, n, rows);
  // Candidate c puts bins [0, c] left and [c + 1, n) right. Step k adds bin k to the left
  // sweep, which completes candidate k, and bin n − 1 − k to the right, completing n − 2 − k.
  alignas(32) double left[kMaxBins][4], right[kMaxBins][4], tl[kMaxBins][4], tr[kMaxBins][4];
  SweepLanes<A> sweep;
  for (int k = 0; k < n - 1; ++k) {
    sweep.add(rows[k], rows[n - 1 - k]).store(left[k], right[n - 2 - k]);
    sweep.tests.store(tl[k], tr[n - 2 - k]);
  }
  // An axis whose centroids all lie in one plane has no split (make_grid's scale 0).
  const double usable[4] = {grid.scale[0] > 0 ? 1.0 : 0.0, grid.scale[1] > 0 ? 1.0 : 0.0,
                            grid.scale[2] > 0 ? 1.0 : 0.0, 0.0};
  return choose<A>(left, right, tl, tr, n - 1, usable, traversal_cost, parent_area);
}

}  // namespace raylane::bvh_build::lanes
