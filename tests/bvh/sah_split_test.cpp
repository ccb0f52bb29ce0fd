// The builder's split choice (src/bvh/sah_split.h) against a plain evaluation of the surface
// area heuristic: for every candidate, the boxes and costs of both sides gathered from the
// bins anew, the cost computed as Wald (2007, §3) states it, and the first cheapest candidate
// taken. The sweep must give the same split and the same cost to the bit, on bins with empty
// runs (whose candidates tie with their neighbours) and flat axes.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "bvh/build_lanes.h"
#include "bvh/sah_split.h"

namespace raylane::bvh_build {
namespace {

// Bins of `n` per axis, about half of them empty, boxes and costs drawn at random.
BinSet random_bins(std::mt19937& rng, int n, BinGrid& grid) {
  std::uniform_real_distribution<float> u(-10.0f, 10.0f), ext(0.0f, 3.0f);
  std::uniform_int_distribution<int> occupied(0, 1), members(1, 5);
  BinSet bins;
  bins.clear(n);
  grid.bins = n;
  for (int a = 0; a < 3; ++a) {
    grid.scale[a] = a == 2 && n % 3 == 0 ? 0.0f : 1.0f;  // sometimes one flat axis
    for (int b = 0; b < n; ++b) {
      if (!occupied(rng)) continue;
      BinBox& box = bins.box[a][b];
      for (int k = 0; k < 3; ++k) {
        box.lo[k] = u(rng);
        box.neg_hi[k] = -(box.lo[k] + ext(rng));
      }
      bins.cost[a][b] = uint64_t(members(rng)) * cost_units(0.3);
    }
  }
  return bins;
}

// One side of the candidate that puts bins [first, last) of `axis` on it.
struct Side {
  Bounds3f box;
  double tests = 0;
};

Side gather(const BinSet& bins, int axis, int first, int last, bool from_right) {
  Side s;
  for (int k = 0; k < last - first; ++k) {
    int b = from_right ? last - 1 - k : first + k;  // the sweep's order of summing
    if (bins.cost[axis][b] == 0) continue;          // an empty bin
    s.box.extend(bins.box[axis][b].bounds());
    s.tests += double(bins.cost[axis][b]) * kCostUnit;
  }
  return s;
}

Split direct_split(const BinSet& bins, const BinGrid& grid, const Bounds3f& parent,
                   double traversal) {
  Split best;
  const double parent_area = std::max(half_area(parent), 1e-300);
  for (int axis = 0; axis < 3; ++axis) {
    if (!(grid.scale[axis] > 0)) continue;
    for (int b = 0; b + 1 < grid.bins; ++b) {
      Side l = gather(bins, axis, 0, b + 1, false), r = gather(bins, axis, b + 1, grid.bins, true);
      double cost =
          traversal + (half_area(l.box) * l.tests + half_area(r.box) * r.tests) / parent_area;
      if (l.tests > 0 && r.tests > 0 && cost < best.cost) best = {axis, b, cost};
    }
  }
  return best;
}

TEST(SahSplit, EveryIsaSweepEqualsTheDirectCosts) {
  std::mt19937 rng(17);
  int ties = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    BinGrid grid;
    BinSet bins = random_bins(rng, 2 + trial % 15 + (trial % 50 == 0 ? 48 : 0), grid);
    Bounds3f parent;
    for (int b = 0; b < grid.bins; ++b)
      if (bins.cost[0][b]) parent.extend(bins.box[0][b].bounds());
    if (parent.empty()) continue;
    Split want = direct_split(bins, grid, parent, 1.0);
    for (Isa isa : supported_isas()) {
      Split got = best_split(bins, grid, parent, 1.0, isa);
      ASSERT_EQ(got.axis, want.axis) << trial << ' ' << isa_name(isa);
      if (want.axis < 0) continue;
      ASSERT_EQ(got.last_left, want.last_left) << trial << ' ' << isa_name(isa);
      ASSERT_EQ(got.cost, want.cost) << trial << ' ' << isa_name(isa);
    }
    if (want.axis < 0) continue;
    // An empty bin after the chosen one gives the same cost: the first must be chosen.
    ties += want.last_left + 1 < grid.bins - 1 && bins.cost[want.axis][want.last_left + 1] == 0;
  }
  EXPECT_GT(ties, 100);  // the tie-breaking was exercised
}

// Small nodes of random boxes, some spread out, some piled up, costing 0.3 or 1: whenever the
// bound says "leaf", the bins say so too (the bound decides only what binning would), and it
// says so for a good share of the bins' leaves (else it saves nothing).
TEST(SahSplit, LeafByBoundOnlyWhereTheBinsMakeALeaf) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int leaves_by_bound = 0, leaves_by_bins = 0, trials = 4000;
  for (int trial = 0; trial < trials; ++trial) {
    const uint32_t n = 2 + trial % 7;
    const float spread = trial % 3 == 0 ? 4.0f : 1.0f, size = 0.2f + 1.5f * u(rng);
    std::vector<BuildPrim> prims(n);
    for (BuildPrim& p : prims) {
      for (int k = 0; k < 3; ++k) {
        p.lo[k] = spread * u(rng);
        p.hi[k] = p.lo[k] + size * u(rng);
      }
      p.ref = PrimRef();
      p.cost = cost_units(trial % 2 ? 0.3 : 1.0);
    }
    NodeBounds nb;
    nb.clear();
    const BuildLanes& lanes = build_lanes(Isa::kSse42);
    lanes.bound(prims.data(), n, nb);
    BinGrid grid = make_grid(nb, std::min<int>(n, 16));
    BinSet bins;
    bins.clear(grid.bins);
    lanes.bin(prims.data(), n, grid, bins);
    Split split = best_split(bins, grid, nb.box.bounds(), 1.0, Isa::kSse42);
    bool bins_say_leaf = binned_cost(bins, grid.bins) <= split.cost;
    leaves_by_bins += bins_say_leaf;
    if (leaf_by_bound(prims.data(), n, nb.box.bounds(), 1.0)) {
      ++leaves_by_bound;
      ASSERT_TRUE(bins_say_leaf) << trial;
    }
  }
  EXPECT_GT(leaves_by_bins, trials / 5);           // 1305: the draws make leaves and splits
  EXPECT_GT(leaves_by_bound, leaves_by_bins / 3);  // 673
}

}  // namespace
}  // namespace raylane::bvh_build
