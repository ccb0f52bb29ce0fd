// The 8-wide collapse (src/bvh/wide.cpp) picks, among all ways to cut the binary tree into
// wide nodes of at most 8 children, one of least expected wide-node visits: the sum of the
// surface areas of the binary nodes that root a wide node. Checked against every cut,
// enumerated one by one on small random scenes (no dynamic programming in the test).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "raylane/bvh/bvh.h"
#include "support/random_scene.h"

namespace raylane {
namespace {

struct Cut {
  int nodes;    // binary nodes in the cut (the wide node's children)
  double cost;  // the wide nodes below them: inner nodes of the cut root wide nodes
};

double least_cost_as_root(const Bvh& bvh, uint32_t b);

// Every cut of b's subtree of at most kWideArity nodes, each with its least cost below.
std::vector<Cut> all_cuts(const Bvh& bvh, uint32_t b) {
  const BvhNode& n = bvh.nodes[b];
  std::vector<Cut> cuts{{1, n.is_leaf() ? 0.0 : least_cost_as_root(bvh, b)}};
  if (n.is_leaf()) return cuts;
  for (const Cut& l : all_cuts(bvh, n.index))
    for (const Cut& r : all_cuts(bvh, n.index + 1))
      if (l.nodes + r.nodes <= kWideArity) cuts.push_back({l.nodes + r.nodes, l.cost + r.cost});
  return cuts;
}

// Inner node b as the root of a wide node: its area plus the best cut of its two subtrees.
double least_cost_as_root(const Bvh& bvh, uint32_t b) {
  const BvhNode& n = bvh.nodes[b];
  double best = std::numeric_limits<double>::infinity();
  for (const Cut& l : all_cuts(bvh, n.index))
    for (const Cut& r : all_cuts(bvh, n.index + 1))
      if (l.nodes + r.nodes <= kWideArity) best = std::min(best, l.cost + r.cost);
  return n.half_area() + best;
}

TEST(WideCollapse, RootsAreTheCutOfLeastArea) {
  for (uint32_t seed = 1; seed <= 12; ++seed) {
    Scene s = testing::random_scene(seed, 4 + int(seed % 4));  // 16 … 28 primitives
    Bvh bvh = build_bvh_and_reorder(s, {.max_leaf = 2, .forced_leaf = 2, .wide_nodes = true});
    ASSERT_FALSE(bvh.nodes[0].is_leaf());
    // A wide node's box, the union of its children's, is that of the binary node it roots.
    double cost = 0;
    for (const WideNode& w : bvh.wide.nodes) {
      BvhNode root;
      for (int axis = 0; axis < 3; ++axis) {
        root.lo[axis] = *std::min_element(w.box[axis][0], w.box[axis][0] + w.arity);
        root.hi[axis] = *std::max_element(w.box[axis][1], w.box[axis][1] + w.arity);
      }
      cost += root.half_area();
    }
    double least = least_cost_as_root(bvh, 0);
    EXPECT_NEAR(cost, least, 1e-12 * least) << "seed " << seed;
  }
}

}  // namespace
}  // namespace raylane
