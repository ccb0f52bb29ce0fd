// Binned SAH build (Wald 2007, "On fast Construction of SAH-based Bounding Volume
// Hierarchies"), top-down. The top levels split each large node with every thread (per-thread
// bins over contiguous chunks, then an in-place parallel partition: parallel_split.h) until
// there are enough subtrees for the threads; then each thread builds whole subtrees alone.
// Every node is one binning pass and one partitioning pass over its prims: the partition
// computes the children's bounds, so no pass only bounds a node. Where a node goes is fixed by
// its prims' range (Pending::desc), so threads never share a counter or a cache line of nodes,
// and the tree copied out depth first (build_output.h) is the same for any thread count.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <memory>

#include "bvh/build_lanes.h"
#include "bvh/build_output.h"
#include "bvh/build_prim.h"
#include "bvh/parallel_split.h"
#include "bvh/sah_split.h"
#include "raylane/bvh/bvh.h"
#include "raylane/scene/scene.h"

namespace raylane {

namespace {

using namespace bvh_build;

static_assert(kMedianSplitDepth + 32 < 256,
              "a node's depth fits its flags byte while building (split_node)");

// A node still to be built: its slot, its prims [begin, end) and their bounds. Its subtree's
// other nodes go to slots [desc, desc + 2·count − 2): its children to desc and desc + 1, the
// left child's subtree after them, then the right child's (a subtree of c prims has at most
// 2c − 1 nodes), so the root's slot 0 and desc 1 place every node of the tree in 2n − 1 slots.
struct Pending {
  uint32_t node, begin, end, depth, desc;
  NodeBounds bounds;

  uint32_t count() const { return end - begin; }
};

// What to do with a node once it is binned (or known to be too deep to bin).
struct Decision {
  bool leaf = false;
  Split split;  // axis −1 and not a leaf: split at the object median
};

class Builder {
 public:
  // Slots live in memory that is not written until a node is made, so the 2n − 1 a build may
  // need cost no resident memory beyond the nodes it makes.
  Builder(BuildPrim* prims, uint32_t count, const BvhConfig& cfg)
      : prims_(prims),
        count_(count),
        cfg_(cfg),
        nodes_(allocate_unwritten<BvhNode>(2 * count)),
        used_(allocate_zeroed_bytes(2 * count)) {}

  // Builds the whole tree with `threads` threads.
  void build(int threads) {
    // A small scene builds in microseconds: no parallel region.
    if (threads < 2 || count_ <= kParallelPrims) {
      NodeBounds bounds;
      bounds.clear();
      lanes_.bound(prims_, count_, bounds);
      build_subtree({0, 0, count_, 0, 1, bounds}, false);
      return;
    }
#pragma omp parallel num_threads(threads)
#pragma omp single
    {
      const int parts = kChunksPerThread * threads;
      Pending root{0, 0, count_,
                   0, 1, bound_in_parallel(lanes_, prims_, count_, count_ > 4096 ? parts : 1)};
      std::vector<Pending> subtrees = split_top_levels(root, threads, parts);
      // Largest first, so the last subtrees to finish are small.
      std::sort(subtrees.begin(), subtrees.end(),
                [](const Pending& a, const Pending& b) { return a.count() > b.count(); });
      // Every task, the ones the subtrees make included, ends at the region's barrier. (Not a
      // taskgroup: GCC 12's libgomp ran all the tasks made inside one on its waiting thread.)
      // The tasks outlive this block, so each takes its own copy of its subtree.
      for (const Pending& p : subtrees) {
        Pending sub = p;
#pragma omp task default(shared) firstprivate(sub)
        build_subtree(sub, true);
      }
    }
  }

  // The slots of the tree made, and which of them were made (compact_tree reads them).
  const BvhNode* slots() const {
    return nodes_.get();
  }
  const uint8_t* used() const {
    return used_.get();
  }
  uint32_t slot_count() const {
    return 2 * count_;
  }

 private:
  // Nodes above max(kChunkPrims, n / (kSubtreesPerThread · threads)) prims are split with
  // every thread (kChunksPerThread chunks each); below, each subtree is a task, which hands its
  // left child of at least kTaskPrims prims to another task, so a thread that runs out of
  // subtrees takes part of another's. Each chunk is a task of about a microsecond, while one
  // thread splits a node of 4096 prims in about 50 (the bunny's top levels were chunked down
  // to 1024 prims).
  static constexpr uint32_t kParallelPrims = 1024;
  static constexpr uint32_t kChunkPrims = 4096;
  static constexpr uint32_t kTaskPrims = 512;
  static constexpr uint32_t kSubtreesPerThread = 8;
  static constexpr int kChunksPerThread = 4;

  std::vector<Pending> split_top_levels(const Pending& root, int threads, int parts) {
    std::vector<Pending> todo = {root}, subtrees;
    if (threads < 2) return todo;
    const uint32_t large = std::max(kChunkPrims, count_ / (kSubtreesPerThread * threads));
    while (!todo.empty()) {
      Pending p = todo.back();
      todo.pop_back();
      if (p.count() <= large) {
        subtrees.push_back(p);
        continue;
      }
      Pending left, right;
      if (!split_node(p, parts, left, right)) continue;  // a leaf (only ever by depth)
      todo.push_back(left), todo.push_back(right);
    }
    return subtrees;
  }

  // Builds the subtree of `p`. With `tasks`, a left child of at least kTaskPrims prims is built
  // by a new task. Tasks only ever wait at the build's end, so no thread picks up a subtree
  // while a node it is binning waits (the trap of bench/README.md).
  void build_subtree(const Pending& p, bool tasks) {
    Pending left, right;
    if (!split_node(p, 1, left, right)) return;
    if (tasks && left.count() >= kTaskPrims) {
#pragma omp task default(shared) firstprivate(left)
      build_subtree(left, true);
      build_subtree(right, true);
      return;
    }
    build_subtree(left, tasks);
    build_subtree(right, tasks);
  }

  // Makes p's node a leaf (returns false) or an inner node whose children are left and right;
  // parts > 1: bins and partitions in that many tasks (parallel_split.h).
  bool split_node(const Pending& p, int parts, Pending& left, Pending& right) {
    BvhNode& n = nodes_.get()[p.node];
    used_.get()[p.node] = 1;
    const Box4& box = p.bounds.box;
    for (int k = 0; k < 3; ++k)
      n.lo[k] = box.lo[k], n.hi[k] = box.hi[k];
    n.flags = uint8_t(p.depth);  // for compact_tree's statistics (it zeroes the byte)
    BinGrid grid = make_grid(p.bounds, std::clamp(int(p.count()), 2, cfg_.bins));
    Decision d = decide(p, grid, parts);
    if (d.leaf) {
      make_leaf(n, p.begin, p.end);
      return false;
    }
    BuildPrim* first = prims_ + p.begin;
    uint32_t mid = p.count() / 2;
    left.bounds.clear(), right.bounds.clear();
    if (d.split.axis >= 0)
      mid = parts > 1 ? partition_in_parallel(lanes_, first, p.count(), grid, d.split.axis,
                                              d.split.last_left, parts, left.bounds, right.bounds)
                      : lanes_.partition(first, p.count(), grid, d.split.axis, d.split.last_left,
                                         left.bounds, right.bounds);
    // The partition classifies by the binning's own arithmetic, so both sides hold prims;
    // the median stands in should they not (and where no split separates the centroids).
    if (d.split.axis < 0 || mid == 0 || mid == p.count()) {
      mid = p.count() / 2;
      left.bounds.clear(), right.bounds.clear();
      lanes_.bound(first, mid, left.bounds);
      lanes_.bound(first + mid, p.count() - mid, right.bounds);
    }
    const uint32_t child = p.desc;
    n.index = child;
    n.count = 0;
    n.axis = uint8_t(std::max(d.split.axis, 0));
    left = {child, p.begin, p.begin + mid, p.depth + 1, child + 2, left.bounds};
    right = {child + 1, p.begin + mid, p.end, p.depth + 1, child + 2 * mid, right.bounds};
    return true;
  }

  // Leaf or split, by the SAH: a node may be a leaf when it has at most max_leaf prims (or at
  // most forced_leaf and no split separates its centroids), and is one if that costs no more
  // than the best split. Deep in the tree, nodes split at the object median so that traversal
  // stacks cannot overflow. Half the nodes binned are leaves; most small ones are known to be
  // without bins (leaf_by_bound).
  Decision decide(const Pending& p, const BinGrid& grid, int parts) const {
    const uint32_t count = p.count();
    if (count == 1) return {true, {}};
    if (p.depth >= kMedianSplitDepth) return {count <= uint32_t(cfg_.max_leaf), {}};
    if (count <= uint32_t(cfg_.max_leaf) &&
        leaf_by_bound(prims_ + p.begin, count, p.bounds.box.bounds(), cfg_.traversal_cost))
      return {true, {}};
    BinSet bins;
    if (parts > 1) {
      bin_in_parallel(lanes_, prims_ + p.begin, count, grid, parts, bins);
    } else {
      bins.clear(grid.bins);
      lanes_.bin(prims_ + p.begin, count, grid, bins);
    }
    Split split = best_split(bins, grid, p.bounds.box.bounds(), cfg_.traversal_cost, isa_);
    bool may_leaf =
        count <= uint32_t(cfg_.max_leaf) || (split.axis < 0 && count <= uint32_t(cfg_.forced_leaf));
    return {may_leaf && binned_cost(bins, grid.bins) <= split.cost, split};
  }

  // Refs in a leaf are sorted by kind (then row), so the leaf is a few runs of one kind.
  void make_leaf(BvhNode& n, uint32_t begin, uint32_t end) {
    std::sort(prims_ + begin, prims_ + end,
              [](const BuildPrim& a, const BuildPrim& b) { return a.ref < b.ref; });
    n.index = begin;
    n.count = uint16_t(end - begin);
    n.axis = 0;
  }

  BuildPrim* const prims_;
  const uint32_t count_;
  const BvhConfig& cfg_;
  const Isa isa_ = best_isa();
  const BuildLanes& lanes_ = build_lanes(isa_);
  MallocPtr<BvhNode> nodes_;
  MallocPtr<uint8_t> used_;  // 1 where a slot holds a node (threads write different bytes)
};

}  // namespace

BvhConfig render_bvh_config(const Scene& scene) {
  BvhConfig config;
  config.wide_nodes = scene.primitive_count() >= kWideNodesFrom;
  return config;
}

Bvh build_bvh_and_reorder(Scene& scene, const BvhConfig& config) {
  auto start = std::chrono::steady_clock::now();
  Bvh bvh;
  const int threads = omp_in_parallel() ? 1 : omp_get_max_threads();
  const uint32_t count = uint32_t(scene.primitive_count());
  if (count == 0) return bvh;
  MallocPtr<BuildPrim> prims = gather(scene, threads);
  BvhConfig cfg = config;
  cfg.bins = std::clamp(cfg.bins, 2, kMaxBins);
  {
    Builder builder(prims.get(), count, cfg);
    builder.build(threads);
    compact_tree(builder.slots(), builder.used(), builder.slot_count(), prims.get(),
                 cfg.traversal_cost, threads, bvh.nodes, bvh.stats);
  }
  bvh.refs = take_refs(prims.get(), count, threads);
  prims.reset();
  bvh.source_rows = permute_scene(scene, bvh.refs);
  bvh.refs = index_leaves(bvh.nodes, bvh.refs, threads);
  if (cfg.wide_nodes) bvh.wide = collapse_to_wide(bvh);
  bvh.stats.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace raylane
