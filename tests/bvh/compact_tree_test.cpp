// The builder's slots compacted into the node array (src/bvh/compact_tree.cpp) against a plain
// depth-first copy: random trees laid out in slots as the builder lays them out (a node of c
// prims owns the 2c − 2 slots after its children's pair; the slots no node uses hold garbage)
// must give the same array, node for node, and the same statistics, at 1 and 2 threads.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "bvh/build_output.h"
#include "bvh/sah_split.h"
#include "raylane/prims/prim_list.h"

namespace raylane::bvh_build {
namespace {

struct SlotTree {
  std::vector<BvhNode> slots;
  std::vector<uint8_t> used;
  std::vector<BuildPrim> prims;
};

// Places the node of prims [begin, end) at `slot`, its descendants from `desc` (build.cpp's
// Pending), with a random split, a leaf at random below 9 prims, and a random box.
void place(SlotTree& t, std::mt19937& rng, uint32_t slot, uint32_t begin, uint32_t end,
           uint32_t depth, uint32_t desc, float scale) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  BvhNode& n = t.slots[slot];
  t.used[slot] = 1;
  for (int k = 0; k < 3; ++k)
    n.lo[k] = -scale * (0.5f + u(rng)), n.hi[k] = scale * (0.5f + u(rng));
  n.flags = uint8_t(depth);
  const uint32_t count = end - begin;
  if (count == 1 || (count <= 8 && u(rng) < 0.5f)) {
    n.index = begin, n.count = uint16_t(count), n.axis = 0;
    return;
  }
  const uint32_t mid = 1 + std::uniform_int_distribution<uint32_t>(0, count - 2)(rng);
  n.index = desc, n.count = 0, n.axis = uint8_t(depth % 3);
  place(t, rng, desc, begin, begin + mid, depth + 1, desc + 2, scale * 0.8f);
  place(t, rng, desc + 1, begin + mid, end, depth + 1, desc + 2 * mid, scale * 0.8f);
}

SlotTree random_slot_tree(uint32_t prims, uint32_t seed) {
  std::mt19937 rng(seed);
  SlotTree t;
  t.slots.resize(2 * prims);
  std::memset(static_cast<void*>(t.slots.data()), 0xAB, t.slots.size() * sizeof(BvhNode));
  t.used.assign(2 * prims, 0);
  t.prims.resize(prims);
  for (uint32_t i = 0; i < prims; ++i)
    t.prims[i].ref = PrimRef(PrimTag(i % kPrimKindCount), i);
  place(t, rng, 0, 0, prims, 0, 1, 100.0f);
  return t;
}

// The depth-first copy: each node's children adjacent, placed when their parent is, the left
// subtree's pairs before the right's; statistics summed in that order.
void reference_copy(const SlotTree& t, std::vector<BvhNode>& out, BvhStats& s) {
  const double root_area = half_area(t.slots[0].bounds());
  auto copy = [&](uint32_t slot) {
    BvhNode n = t.slots[slot];
    const uint32_t depth = n.flags;
    n.flags = 0;
    out.push_back(n);
    const double rel = half_area(n.bounds()) / root_area;
    if (!n.is_leaf()) {
      ++s.inner_nodes, s.sah_cost += rel;
      return;
    }
    ++s.leaves, s.depth = std::max(s.depth, depth);
    for (uint32_t i = n.index; i < n.index + n.count; ++i)
      s.sah_cost += rel * kind_sah_test_cost(t.prims[i].ref.tag());
    if (s.leaf_size_histogram.size() <= n.count) s.leaf_size_histogram.resize(n.count + 1);
    ++s.leaf_size_histogram[n.count];
  };
  std::vector<std::pair<uint32_t, uint32_t>> stack;  // (slot, place in out)
  copy(0);
  if (!t.slots[0].is_leaf()) stack.push_back({0, 0});
  while (!stack.empty()) {
    auto [slot, at] = stack.back();
    stack.pop_back();
    const uint32_t child = t.slots[slot].index, first = uint32_t(out.size());
    out[at].index = first;
    copy(child), copy(child + 1);
    for (uint32_t k : {1u, 0u})
      if (!t.slots[child + k].is_leaf()) stack.push_back({child + k, first + k});
  }
}

TEST(CompactTree, EqualsTheDepthFirstCopyAtAnyThreadCount) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    for (uint32_t prims : {1u, 2u, 37u, 40000u}) {  // the last copied by tasks
      SlotTree t = random_slot_tree(prims, seed);
      std::vector<BvhNode> want;
      BvhStats want_stats;
      reference_copy(t, want, want_stats);
      double sah_at_one = 0;
      for (int threads : {1, 2}) {
        std::vector<BvhNode> got;
        BvhStats s;
        compact_tree(t.slots.data(), t.used.data(), uint32_t(t.slots.size()), t.prims.data(), 1.0,
                     threads, got, s);
        ASSERT_EQ(got.size(), want.size()) << seed << ' ' << prims;
        for (std::size_t i = 0; i < got.size(); ++i)
          ASSERT_EQ(std::memcmp(&got[i], &want[i], sizeof(BvhNode)), 0) << "node " << i;
        EXPECT_EQ(s.inner_nodes, want_stats.inner_nodes);
        EXPECT_EQ(s.leaves, want_stats.leaves);
        EXPECT_EQ(s.depth, want_stats.depth);
        EXPECT_EQ(s.leaf_size_histogram, want_stats.leaf_size_histogram);
        // Summed by subtrees, then in their order: the same sum up to rounding, and the same
        // bits for any thread count.
        EXPECT_NEAR(s.sah_cost, want_stats.sah_cost, 1e-12 * want_stats.sah_cost);
        if (threads == 1) sah_at_one = s.sah_cost;
        EXPECT_EQ(s.sah_cost, sah_at_one);
      }
    }
  }
}

}  // namespace
}  // namespace raylane::bvh_build
