// The BVH: a binary tree of boxes over the PrimRefs of every kind at once, built top-down
// with the binned surface area heuristic (Wald 2007, "On fast Construction of SAH-based
// Bounding Volume Hierarchies"). Leaves hold refs sorted by kind, and the scene's tables are
// permuted into leaf order, so each leaf is a few runs of contiguous rows of one kind
// (docs/design.md, "BVH"). The BVH never names a primitive kind.
#pragma once

#include <cstdint>
#include <vector>

#include "raylane/bvh/wide_bvh.h"
#include "raylane/core/bounds3.h"
#include "raylane/core/prim_ref.h"

namespace raylane {

struct Scene;

// 32 bytes. Siblings are adjacent: an inner node's children are nodes[index] and
// nodes[index + 1].
struct BvhNode {
  float lo[3];
  float hi[3];
  // Inner: first child. Leaf of one kind (kOneKind): the PrimRef bits of its first row, its
  // rows being contiguous; leaf of several kinds: its first ref in Bvh::refs.
  uint32_t index;
  uint16_t count;  // 0 for an inner node; a leaf's number of primitives
  uint8_t axis;    // inner: the split axis (children ordered along it); leaf: unused
  uint8_t flags;   // kOneKind or 0
  static constexpr uint8_t kOneKind = 1;

  // Leaves every field unset: the builder sizes the node array and its threads write each
  // node once (value-initialising a million nodes first took 8.5 ms of one thread).
  BvhNode() {}

  bool is_leaf() const { return count > 0; }
  bool is_one_kind() const { return flags & kOneKind; }
  Bounds3f bounds() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
  // Half the surface area, in double (the wide collapse's cost: src/bvh/wide.cpp).
  double half_area() const {
    double dx = double(hi[0]) - lo[0], dy = double(hi[1]) - lo[1], dz = double(hi[2]) - lo[2];
    return dx * dy + dy * dz + dz * dx;
  }
};
static_assert(sizeof(BvhNode) == 32);

// Traversal stacks hold this many entries; the builder keeps the depth below it by splitting
// at the object median below kMedianSplitDepth (median splits add at most log2(n) ≤ 29 more).
inline constexpr int kBvhStackSize = 64;
inline constexpr uint32_t kMedianSplitDepth = 32;

struct BvhConfig {
  int bins = 16;                // 2 … 64
  int max_leaf = 8;             // a leaf may be made when it has at most this many refs...
  int forced_leaf = 32;         // ...and must be split above this many, whatever the SAH says
  double traversal_cost = 1.0;  // SAH cost of visiting an inner node (a primitive test costs
                                // its kind's sah_test_cost: prims/prim_list.h)
  bool wide_nodes = false;  // also collapse the tree to 8-wide nodes (Bvh::wide), for single rays
};

struct BvhStats {
  double build_seconds = 0;
  uint32_t inner_nodes = 0, leaves = 0, depth = 0;
  double sah_cost = 0;  // expected cost of a random ray, relative to the root box
  std::vector<uint32_t> leaf_size_histogram;  // [n] = number of leaves with n refs
};

struct Bvh {
  std::vector<BvhNode> nodes;  // nodes[0] is the root (a leaf if the scene is tiny)
  // The contents of the leaves that hold more than one kind, sorted by kind (rows are the
  // scene's rows after permutation). A leaf of one kind needs none: it names its first row
  // (BvhNode::index), 4 bytes a primitive saved on most scenes (bench/README.md, "Quantised wide
  // nodes (not kept), leaves of one kind without refs").
  std::vector<PrimRef> refs;
  // source_rows[k][r]: the row that row r of kind k's table had before the build permuted it
  // (to report results in the input's order, e.g. triangle indices of a soup). Not used by
  // traversal, so not counted in bytes().
  std::vector<std::vector<uint32_t>> source_rows;
  // The same tree collapsed to 8-wide nodes, for single rays (trace/ray_traverse.h); built
  // only when BvhConfig::wide_nodes asks (it costs memory: bench/README.md).
  WideBvh wide;
  BvhStats stats;

  bool empty() const { return nodes.empty(); }
  std::size_t bytes() const {
    return nodes.size() * sizeof(BvhNode) + refs.size() * sizeof(PrimRef) + wide.bytes();
  }
};

// Calls f(head, rows) for each run of one kind in a mixed leaf's refs [first, first + count):
// rows head.row() … head.row() + rows − 1 of head's kind (the tables are permuted into leaf
// order, so a run's rows are contiguous). The 8-wide tree's leaves hold the same refs.
template <class F>
inline void for_each_ref_run(const Bvh& bvh, uint32_t first, uint32_t count, F&& f) {
  uint32_t i = first, end = first + count;
  while (i < end) {
    PrimRef head = bvh.refs[i];
    uint32_t j = i + 1;
    while (j < end && bvh.refs[j].tag() == head.tag())
      ++j;
    f(head, j - i);
    i = j;
  }
}
// The same for every run of `leaf`: one run of a one-kind leaf, or its refs' runs.
template <class F>
inline void for_each_run(const Bvh& bvh, const BvhNode& leaf, F&& f) {
  if (leaf.is_one_kind()) return f(PrimRef::from_bits(leaf.index), uint32_t(leaf.count));
  for_each_ref_run(bvh, leaf.index, uint32_t(leaf.count), f);
}

// The BVH raylane's commands build (render, view, trace, info, and the benchmarks that measure
// them): with wide nodes from kWideNodesFrom primitives on, so that a packet whose lanes thin
// out goes on as single rays over the 8-wide tree (the hybrid, trace/packet_traverse.h): the
// same answers bit for bit, faster on incoherent rays once the tree is deep enough to pay for
// the wide nodes' memory (bench/README.md, "The render's tracer").
inline constexpr std::size_t kWideNodesFrom = 4096;
BvhConfig render_bvh_config(const Scene& scene);

// Builds the BVH over every primitive of `scene` and reorders the scene: its tables are permuted
// into leaf order (Scene::permute; Bvh::source_rows maps the new rows to the old), so that a
// leaf's primitives are consecutive rows. A scene without primitives gives an empty BVH.
Bvh build_bvh_and_reorder(Scene& scene, const BvhConfig& config = {});

}  // namespace raylane
