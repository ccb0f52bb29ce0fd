// Binned SAH build (Wald 2007, "On fast Construction of SAH-based Bounding Volume
// Hierarchies"), top-down. The top levels split each large node with every thread (per-thread
// bins over contiguous chunks, then an in-place parallel partition: parallel_split.h) until
// there are enough subtrees for the threads; then each thread builds whole subtrees alone.
// Every node is one binning pass and one partitioning pass over its prims: the partition
// computes the children's bounds, so no pass only bounds a node.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <memory>

#include "bvh/build_prim.h"
#include "bvh/parallel_split.h"
#include "bvh/sah_split.h"
#include "raylane/bvh/bvh.h"
#include "raylane/scene/scene.h"

namespace raylane {

namespace {

using namespace bvh_build;

// A node still to be built: its prims [begin, end) and their bounds.
struct Pending {
  uint32_t node, begin, end, depth;
  NodeBounds bounds;

  uint32_t count() const { return end - begin; }
};

// What to do with a node once it is binned (or known to be too deep to bin).
struct Decision {
  bool leaf = false;
  Split split;  // axis −1 and not a leaf: split at the object median
};

// Nodes live in memory that is not written until a node is made, so the 2n − 1 slots a
// build may need cost no resident memory beyond the nodes it makes (BvhNode is an aggregate,
// so its objects begin when written).
struct FreeNodes {
  void operator()(BvhNode* p) const { std::free(p); }
};

class Builder {
 public:
  Builder(std::vector<BuildPrim>& prims, const BvhConfig& cfg)
      : prims_(prims),
        cfg_(cfg),
        nodes_(static_cast<BvhNode*>(std::malloc(sizeof(BvhNode) * (2 * prims.size())))) {
    if (!nodes_) throw std::bad_alloc();
  }

  // Builds the whole tree with `threads` threads; returns the depth of its deepest leaf.
  uint32_t build(int threads) {
    const uint32_t count = uint32_t(prims_.size());
    // A small scene builds in microseconds: no parallel region.
    if (threads < 2 || count <= kParallelPrims) {
      NodeBounds bounds;
      bounds.clear();
      bound_prims(prims_.data(), count, bounds);
      return build_subtree({0, 0, count, 0, bounds});
    }
    std::vector<uint32_t> depths;
#pragma omp parallel num_threads(threads)
#pragma omp single
    {
      const int parts = kChunksPerThread * threads;
      const uint32_t n = uint32_t(prims_.size());
      Pending root{0, 0, n, 0, bound_in_parallel(prims_.data(), n, n > 4096 ? parts : 1)};
      std::vector<Pending> subtrees = split_top_levels(root, threads, parts);
      // Largest first, so the last subtrees to finish are small.
      std::sort(subtrees.begin(), subtrees.end(),
                [](const Pending& a, const Pending& b) { return a.count() > b.count(); });
      depths.resize(subtrees.size());
      for (std::size_t i = 0; i < subtrees.size(); ++i) {
#pragma omp task default(shared) firstprivate(i)
        depths[i] = build_subtree(subtrees[i]);
      }
#pragma omp taskwait
    }
    return *std::max_element(depths.begin(), depths.end());
  }

  std::vector<BvhNode> take_nodes() const {
    return std::vector<BvhNode>(nodes_.get(), nodes_.get() + next_node_.load());
  }

 private:
  // Subtrees above this many prims are split with every thread (kChunksPerThread chunks
  // each); 8 subtrees per thread below it balance the threads' work (siblings differ in size).
  static constexpr uint32_t kParallelPrims = 1024;
  static constexpr uint32_t kSubtreesPerThread = 8;
  static constexpr int kChunksPerThread = 4;

  std::vector<Pending> split_top_levels(const Pending& root, int threads, int parts) {
    std::vector<Pending> todo = {root}, subtrees;
    if (threads < 2) return todo;
    const uint32_t large =
        std::max(kParallelPrims, uint32_t(prims_.size() / (kSubtreesPerThread * threads)));
    while (!todo.empty()) {
      Pending p = todo.back();
      todo.pop_back();
      if (p.count() <= large) {
        subtrees.push_back(p);
        continue;
      }
      Pending left, right;
      split_node(p, parts, left, right);
      todo.push_back(left), todo.push_back(right);
    }
    return subtrees;
  }

  // Builds the subtree of `p` on the calling thread; returns its deepest leaf's depth.
  uint32_t build_subtree(const Pending& p) {
    Pending left, right;
    if (!split_node(p, 1, left, right)) return p.depth;
    return std::max(build_subtree(left), build_subtree(right));
  }

  // Makes p's node a leaf (returns false) or an inner node whose children are left and right;
  // parts > 1: bins and partitions in that many tasks (parallel_split.h).
  bool split_node(const Pending& p, int parts, Pending& left, Pending& right) {
    BvhNode& n = nodes_.get()[p.node];
    const Box4& box = p.bounds.box;
    for (int k = 0; k < 3; ++k)
      n.lo[k] = box.lo[k], n.hi[k] = box.hi[k];
    n.pad = 0;
    BinGrid grid = make_grid(p.bounds, std::clamp(int(p.count()), 2, cfg_.bins));
    Decision d = decide(p, grid, parts);
    if (d.leaf) {
      make_leaf(n, p.begin, p.end);
      return false;
    }
    BuildPrim* first = prims_.data() + p.begin;
    uint32_t mid = p.count() / 2;
    left.bounds.clear(), right.bounds.clear();
    if (d.split.axis >= 0)
      mid = parts > 1 ? partition_in_parallel(first, p.count(), grid, d.split.axis,
                                              d.split.last_left, parts, left.bounds, right.bounds)
                      : partition_prims(first, p.count(), grid, d.split.axis, d.split.last_left,
                                        left.bounds, right.bounds);
    // The partition classifies by the binning's own arithmetic, so both sides hold prims;
    // the median stands in should they not (and where no split separates the centroids).
    if (d.split.axis < 0 || mid == 0 || mid == p.count()) {
      mid = p.count() / 2;
      left.bounds.clear(), right.bounds.clear();
      bound_prims(first, mid, left.bounds);
      bound_prims(first + mid, p.count() - mid, right.bounds);
    }
    uint32_t child = next_node_.fetch_add(2);
    n.index = child;
    n.count = 0;
    n.axis = uint8_t(std::max(d.split.axis, 0));
    left = {child, p.begin, p.begin + mid, p.depth + 1, left.bounds};
    right = {child + 1, p.begin + mid, p.end, p.depth + 1, right.bounds};
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
        leaf_by_bound(prims_.data() + p.begin, count, p.bounds.box.bounds(), cfg_.traversal_cost))
      return {true, {}};
    BinSet bins;
    if (parts > 1) {
      bin_in_parallel(prims_.data() + p.begin, count, grid, parts, bins);
    } else {
      bins.clear(grid.bins);
      bin_prims(prims_.data() + p.begin, count, grid, bins);
    }
    Split split = best_split(bins, grid, p.bounds.box.bounds(), cfg_.traversal_cost, isa_);
    bool may_leaf =
        count <= uint32_t(cfg_.max_leaf) || (split.axis < 0 && count <= uint32_t(cfg_.forced_leaf));
    return {may_leaf && binned_cost(bins, grid.bins) <= split.cost, split};
  }

  // Refs in a leaf are sorted by kind (then row), so the leaf is a few runs of one kind.
  void make_leaf(BvhNode& n, uint32_t begin, uint32_t end) {
    std::sort(prims_.begin() + begin, prims_.begin() + end,
              [](const BuildPrim& a, const BuildPrim& b) { return a.ref < b.ref; });
    n.index = begin;
    n.count = uint16_t(end - begin);
    n.axis = 0;
  }

  std::vector<BuildPrim>& prims_;
  const BvhConfig& cfg_;
  const Isa isa_ = best_isa();
  std::unique_ptr<BvhNode, FreeNodes> nodes_;
  // On a cache line of its own: every node of both threads takes its children from it.
  alignas(64) std::atomic<uint32_t> next_node_{1};
};

// One record per primitive of every kind, filled by all threads.
std::vector<BuildPrim> gather(const Scene& scene, int threads) {
  std::vector<BuildPrim> prims(scene.primitive_count());
  std::size_t offset = 0;
  PrimKinds::for_each([&](auto kind) {
    using Kind = decltype(kind);
    const auto& table = scene.table<Kind>();
    constexpr uint32_t cost = cost_units(Kind::sah_test_cost);
    static_assert(cost > 0, "a prim of no cost would make a bin look empty (BinSet)");
    const int64_t rows = table.size();
    BuildPrim* out = prims.data() + offset;
#pragma omp parallel for num_threads(threads) if (rows > 4096)
    for (int64_t row = 0; row < rows; ++row) {
      Bounds3f b = table.bounds(uint32_t(row));
      out[row] = {{b.lo.x, b.lo.y, b.lo.z},
                  PrimRef(tag_of<Kind>, uint32_t(row)),
                  {b.hi.x, b.hi.y, b.hi.z},
                  cost};
    }
    offset += rows;
  });
  return prims;
}

// Reorders every table into leaf order (Scene::permute) and rewrites the refs to the new rows;
// returns, per kind, the old row of each new row.
std::vector<std::vector<uint32_t>> permute_scene(Scene& scene, std::vector<PrimRef>& refs) {
  std::vector<std::vector<uint32_t>> order(kPrimKindCount);
  for (PrimRef r : refs)
    order[uint32_t(r.tag())].push_back(r.row());
  std::vector<std::vector<uint32_t>> new_row = scene.permute(order);
  for (PrimRef& r : refs)
    r = PrimRef(r.tag(), new_row[uint32_t(r.tag())][r.row()]);
  return order;
}

void collect_stats(const Bvh& bvh, const BvhConfig& cfg, BvhStats& s) {
  double root_area = std::max(half_area(bvh.nodes[0].bounds()), 1e-300);
  for (const BvhNode& n : bvh.nodes) {
    double rel = half_area(n.bounds()) / root_area;
    if (n.is_leaf()) {
      ++s.leaves;
      for (uint32_t i = n.index; i < n.index + n.count; ++i)
        s.sah_cost += rel * kind_sah_test_cost(bvh.refs[i].tag());
      if (s.leaf_size_histogram.size() <= n.count) s.leaf_size_histogram.resize(n.count + 1);
      ++s.leaf_size_histogram[n.count];
    } else {
      ++s.inner_nodes;
      s.sah_cost += rel * cfg.traversal_cost;
    }
  }
}

}  // namespace

Bvh build_bvh(Scene& scene, const BvhConfig& config) {
  auto start = std::chrono::steady_clock::now();
  Bvh bvh;
  const int threads = omp_in_parallel() ? 1 : omp_get_max_threads();
  std::vector<BuildPrim> prims = gather(scene, threads);
  if (prims.empty()) return bvh;
  BvhConfig cfg = config;
  cfg.bins = std::clamp(cfg.bins, 2, kMaxBins);
  uint32_t depth = 0;
  {
    Builder builder(prims, cfg);
    depth = builder.build(threads);
    bvh.nodes = builder.take_nodes();
  }
  bvh.refs.resize(prims.size());
  for (std::size_t i = 0; i < prims.size(); ++i)
    bvh.refs[i] = prims[i].ref;
  std::vector<BuildPrim>().swap(prims);
  bvh.source_rows = permute_scene(scene, bvh.refs);
  bvh.stats.depth = depth;
  collect_stats(bvh, cfg, bvh.stats);
  if (cfg.wide_nodes) bvh.wide = collapse_to_wide(bvh);
  bvh.stats.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace raylane
