// Binned SAH build (Wald 2007), top-down, parallel over subtrees with OpenMP tasks.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include "raylane/bvh/bvh.h"
#include "raylane/scene/scene.h"

namespace raylane {

namespace {

struct BuildPrim {
  Bounds3f box;
  Vec3f centroid;
  PrimRef ref;
  float cost;  // SAH cost of testing it: its kind's sah_test_cost
};

struct Split {
  int axis = -1;
  int bins = 0;  // the number of bins the node was binned into
  int bin = 0;   // prims in bins [0, bin] go left
  double cost = std::numeric_limits<double>::infinity();
};

// Surface area in double: float extents up to FLT_MAX would overflow a float product.
double half_area(const Bounds3f& b) {
  if (b.empty()) return 0;
  Vec3d d = Vec3d(b.hi) - Vec3d(b.lo);
  double a = d.x * d.y + d.y * d.z + d.z * d.x;
  return std::isfinite(a) ? a : std::numeric_limits<double>::max();
}

// A finite stand-in for a centroid component (a huge primitive's centroid can be inf − inf).
float finite_or_zero(float v) {
  return std::isfinite(v) ? v : 0.0f;
}

int bin_of(float c, float lo, double scale, int bins) {
  double x = (double(c) - lo) * scale;
  if (!(x > 0)) return 0;  // also catches NaN
  return std::min(bins - 1, int(x));
}

// A bin of the SAH build: a box, a count and the summed test cost of its prims, with no
// default initialisation (clearing unused bins was the build's largest cost).
struct Bin {
  float lo[3], hi[3];
  uint32_t count;
  double cost;

  void clear() {
    for (int k = 0; k < 3; ++k)
      lo[k] = std::numeric_limits<float>::infinity(), hi[k] = -lo[k];
    count = 0;
    cost = 0;
  }
  void add(const BuildPrim& p) {
    for (int k = 0; k < 3; ++k)
      lo[k] = std::min(lo[k], p.box.lo[k]), hi[k] = std::max(hi[k], p.box.hi[k]);
    ++count;
    cost += p.cost;
  }
  Bounds3f box() const {
    Bounds3f b;
    if (count) b = Bounds3f(Vec3f(lo[0], lo[1], lo[2]), Vec3f(hi[0], hi[1], hi[2]));
    return b;
  }
};

class Builder {
 public:
  static constexpr int kMaxBins = 64;
  // Subtrees above this many prims are built as OpenMP tasks: a task costs about a
  // microsecond, a subtree of 512 prims a few hundred, and the bunny (3,674 prims) then
  // builds on both cores (1.42 -> 0.97 ms; with 4096 it never spawned a task).
  static constexpr uint32_t kTaskPrims = 512;

  // Contract: 2 ≤ cfg.bins ≤ kMaxBins.
  Builder(std::vector<BuildPrim>& prims, const BvhConfig& cfg, std::vector<BvhNode>& nodes)
      : prims_(prims), cfg_(cfg), nodes_(nodes) {}

  // Builds the subtree of prims [begin, end) at `node`; returns the depth of its deepest leaf.
  uint32_t build(uint32_t node, uint32_t begin, uint32_t end, uint32_t depth) {
    Bounds3f box, centroids;
    for (uint32_t i = begin; i < end; ++i) {
      box.extend(prims_[i].box);
      centroids.extend(prims_[i].centroid);
    }
    BvhNode& n = nodes_[node];
    for (int k = 0; k < 3; ++k)
      n.lo[k] = box.lo[k], n.hi[k] = box.hi[k];
    uint32_t count = end - begin;
    // Deep in the tree, split at the object median so traversal stacks cannot overflow.
    bool median_only = depth >= kMedianSplitDepth;
    Split split = count > 1 && !median_only ? find_split(begin, end, box, centroids) : Split{};
    double leaf_cost = 0;
    for (uint32_t i = begin; i < end; ++i)
      leaf_cost += prims_[i].cost;
    bool may_leaf = count <= uint32_t(cfg_.max_leaf) ||
                    (split.axis < 0 && !median_only && count <= uint32_t(cfg_.forced_leaf));
    if (count == 1 || (may_leaf && leaf_cost <= split.cost)) {
      make_leaf(n, begin, end);
      return depth;
    }
    uint32_t mid = split.axis >= 0 ? partition(begin, end, split, centroids) : begin + count / 2;
    if (mid == begin || mid == end) mid = begin + count / 2;  // every centroid in one bin
    uint32_t child = next_node_.fetch_add(2);
    n.index = child;
    n.count = 0;
    n.axis = uint8_t(std::max(split.axis, 0));
    uint32_t left_depth = 0, right_depth = 0;
    if (count > kTaskPrims) {
#pragma omp task default(shared) firstprivate(child, begin, mid, depth)
      left_depth = build(child, begin, mid, depth + 1);
      right_depth = build(child + 1, mid, end, depth + 1);
#pragma omp taskwait
    } else {
      left_depth = build(child, begin, mid, depth + 1);
      right_depth = build(child + 1, mid, end, depth + 1);
    }
    return std::max(left_depth, right_depth);
  }

  uint32_t node_count() const {
    return next_node_.load();
  }

 private:
  // One pass over the prims bins all three axes at once (bins live on the stack); then a
  // sweep per axis evaluates every "bins [0, b] go left" split by the SAH.
  // A small node gets as many bins as it has prims: the bins' fixed cost (clearing and
  // sweeping them) dominated the build, paid at every one of the many small nodes.
  Split find_split(uint32_t begin, uint32_t end, const Bounds3f& box, const Bounds3f& centroids) {
    const int bins = std::clamp(int(end - begin), 2, cfg_.bins);
    double scale[3];
    for (int axis = 0; axis < 3; ++axis) {
      double extent = double(centroids.hi[axis]) - centroids.lo[axis];
      scale[axis] = extent > 0 ? bins / extent : 0.0;
    }
    Bins bin;  // uninitialised: only the first `bins` are cleared and used
    bin_prims(begin, end, centroids, scale, bins, bin);
    Split best;
    double parent_area = std::max(half_area(box), 1e-300);
    for (int axis = 0; axis < 3; ++axis) {
      if (!(scale[axis] > 0)) continue;  // all centroids in one plane: no split on this axis
      double right_cost[kMaxBins] = {};
      Bounds3f acc;
      double tests = 0;  // summed test cost of the prims on one side
      for (int b = bins - 1; b > 0; --b) {
        acc.extend(bin[axis][b].box());
        tests += bin[axis][b].cost;
        right_cost[b - 1] = half_area(acc) * tests;
      }
      acc = Bounds3f();
      tests = 0;
      uint32_t n = 0;
      for (int b = 0; b < bins - 1; ++b) {
        acc.extend(bin[axis][b].box());
        tests += bin[axis][b].cost;
        n += bin[axis][b].count;
        double cost = cfg_.traversal_cost + (half_area(acc) * tests + right_cost[b]) / parent_area;
        if (n > 0 && n < end - begin && cost < best.cost) best = {axis, bins, b, cost};
      }
    }
    return best;
  }

  using Bins = Bin[3][kMaxBins];

  // Clears the first `bins` bins of each axis and adds prims [begin, end) to them.
  void bin_prims(uint32_t begin, uint32_t end, const Bounds3f& centroids, const double* scale,
                 int bins, Bins& bin) const {
    for (int axis = 0; axis < 3; ++axis)
      for (int b = 0; b < bins; ++b)
        bin[axis][b].clear();
    for (uint32_t i = begin; i < end; ++i) {
      const BuildPrim& p = prims_[i];
      for (int axis = 0; axis < 3; ++axis) {
        int b = bin_of(p.centroid[axis], centroids.lo[axis], scale[axis], bins);
        bin[axis][b].add(p);
      }
    }
  }

  uint32_t partition(uint32_t begin, uint32_t end, const Split& s, const Bounds3f& centroids) {
    double extent = double(centroids.hi[s.axis]) - centroids.lo[s.axis];
    double scale = s.bins / extent;
    auto it = std::partition(prims_.begin() + begin, prims_.begin() + end, [&](const BuildPrim& p) {
      return bin_of(p.centroid[s.axis], centroids.lo[s.axis], scale, s.bins) <= s.bin;
    });
    return uint32_t(it - prims_.begin());
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
  std::vector<BvhNode>& nodes_;
  // On a cache line of its own: every node of both threads takes its children from it.
  alignas(64) std::atomic<uint32_t> next_node_{1};
};

std::vector<BuildPrim> gather(const Scene& scene) {
  std::vector<BuildPrim> prims;
  prims.reserve(scene.primitive_count());
  PrimKinds::for_each([&](auto kind) {
    using Kind = decltype(kind);
    const auto& table = scene.table<Kind>();
    const float cost = float(Kind::sah_test_cost);
    for (uint32_t row = 0; row < table.size(); ++row) {
      Bounds3f b = table.bounds(row);
      Vec3f c = b.centroid();
      prims.push_back({b,
                       {finite_or_zero(c.x), finite_or_zero(c.y), finite_or_zero(c.z)},
                       PrimRef(tag_of<Kind>, row),
                       cost});
    }
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
  std::vector<BuildPrim> prims = gather(scene);
  if (prims.empty()) return bvh;
  bvh.nodes.resize(2 * prims.size());
  BvhConfig cfg = config;
  cfg.bins = std::clamp(cfg.bins, 2, Builder::kMaxBins);
  Builder builder(prims, cfg, bvh.nodes);
  uint32_t depth = 0;
#pragma omp parallel
#pragma omp single
  depth = builder.build(0, 0, uint32_t(prims.size()), 0);
  bvh.nodes.resize(builder.node_count());
  bvh.refs.reserve(prims.size());
  for (const BuildPrim& p : prims)
    bvh.refs.push_back(p.ref);
  bvh.source_rows = permute_scene(scene, bvh.refs);
  bvh.stats.depth = depth;
  collect_stats(bvh, cfg, bvh.stats);
  if (cfg.wide_nodes) bvh.wide = collapse_to_wide(bvh);
  bvh.stats.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace raylane
