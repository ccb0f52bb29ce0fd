// Collapsing the binary BVH into 8-wide nodes of least expected wide-node visits (below). The
// greedy rule it replaced (Wald et al. 2008, "Getting Rid of Packets", §3: open the largest
// child until the node is full) left the lattice's wide nodes far from full (bench/README.md,
// "The lattice's bytes per primitive, the 8-wide collapse by least visits").
#include <algorithm>
#include <array>
#include <limits>

#include "raylane/bvh/bvh.h"
#include "raylane/bvh/wide_bvh.h"

namespace raylane {

namespace {

// The collapse that minimises the expected number of wide-node visits of a ray, by dynamic
// programming over the binary tree (after Ylitie, Karras, Laine 2017, "Efficient Incoherent
// Ray Traversal on GPUs Using Compressed Wide BVHs", §3.1, with the leaves kept as they are):
// a wide node rooted at binary node n costs its surface area plus the cost of the wide nodes
// under it, and its children are a cut of n's subtree of at most 8 nodes. best[n][k] is the
// least cost of a cut of n's subtree with at most k + 1 nodes; take[n][k] how many of them go
// to n's first child (0: n itself is the cut).
struct CollapsePlan {
  std::vector<std::array<double, kWideArity>> best;
  std::vector<std::array<uint8_t, kWideArity>> take;
};

// Fills the plan for the subtree of binary node `b`, children first.
void plan_subtree(const Bvh& bvh, uint32_t b, CollapsePlan& p) {
  const BvhNode& n = bvh.nodes[b];
  if (n.is_leaf()) {
    p.best[b].fill(0.0);  // a leaf is a child slot whatever the collapse
    p.take[b].fill(0);
    return;
  }
  plan_subtree(bvh, n.index, p);
  plan_subtree(bvh, n.index + 1, p);
  const auto &l = p.best[n.index], &r = p.best[n.index + 1];
  // Opened into k + 1 ≥ 2 slots: j + 1 for the first child, k − j for the second.
  std::array<double, kWideArity> open;
  std::array<uint8_t, kWideArity> split{};
  for (int k = 1; k < kWideArity; ++k) {
    open[k] = std::numeric_limits<double>::infinity();
    for (int j = 0; j < k; ++j)
      if (l[j] + r[k - 1 - j] < open[k]) open[k] = l[j] + r[k - 1 - j], split[k] = uint8_t(j + 1);
  }
  const double as_node = n.half_area() + open[kWideArity - 1];  // n as a wide node of its own
  p.best[b][0] = as_node;
  p.take[b][0] = 0;
  for (int k = 1; k < kWideArity; ++k) {
    bool keep = as_node <= open[k];
    p.best[b][k] = keep ? as_node : open[k];
    p.take[b][k] = keep ? 0 : split[k];
  }
}

// Appends the cut of binary node b's subtree with at most k + 1 nodes that the plan chose.
void append_cut(const Bvh& bvh, const CollapsePlan& p, uint32_t b, int k, uint32_t* out, int& n) {
  const int j = p.take[b][k];
  if (j == 0) {
    out[n++] = b;
    return;
  }
  const uint32_t first = bvh.nodes[b].index;
  append_cut(bvh, p, first, j - 1, out, n);
  append_cut(bvh, p, first + 1, k - j, out, n);
}

// The binary nodes that become the children of the wide node rooted at inner node `b`.
int gather_children(const Bvh& bvh, const CollapsePlan& p, uint32_t b,
                    uint32_t (&out)[kWideArity]) {
  const BvhNode& inner = bvh.nodes[b];
  const auto &l = p.best[inner.index], &r = p.best[inner.index + 1];
  int j_best = 1;
  for (int j = 1; j < kWideArity; ++j)
    if (l[j - 1] + r[kWideArity - 1 - j] < l[j_best - 1] + r[kWideArity - 1 - j_best]) j_best = j;
  int n = 0;
  append_cut(bvh, p, inner.index, j_best - 1, out, n);
  append_cut(bvh, p, inner.index + 1, kWideArity - 1 - j_best, out, n);
  return n;
}

void clear_slot(WideNode& w, int k) {
  const float inf = std::numeric_limits<float>::infinity();
  for (int axis = 0; axis < 3; ++axis)
    w.box[axis][0][k] = inf, w.box[axis][1][k] = -inf;
  w.child[k] = 0;
  w.count[k] = 0;
}

void set_slot(WideNode& w, int k, const BvhNode& b) {
  for (int axis = 0; axis < 3; ++axis)
    w.box[axis][0][k] = b.lo[axis], w.box[axis][1][k] = b.hi[axis];
  w.child[k] = b.index;  // a leaf's first row or ref; an inner child's index is set by the caller
  w.count[k] = b.count;
  if (b.is_leaf() && b.is_one_kind()) w.one_kind |= uint8_t(1u << k);
}

// Makes the wide node for binary node `binary` at wide.nodes[slot], then its inner children,
// depth first.
void collapse(const Bvh& bvh, const CollapsePlan& plan, uint32_t binary, uint32_t slot,
              WideBvh& wide) {
  uint32_t children[kWideArity];
  const BvhNode& b = bvh.nodes[binary];
  int n = 1;
  if (b.is_leaf()) {
    children[0] = binary;  // a tree that is one leaf: a root with one child
  } else {
    n = gather_children(bvh, plan, binary, children);
  }
  WideNode w{};
  for (int k = 0; k < kWideArity; ++k) {
    if (k < n) {
      set_slot(w, k, bvh.nodes[children[k]]);
    } else {
      clear_slot(w, k);
    }
  }
  w.arity = uint8_t(n);
  wide.nodes[slot] = w;
  for (int k = 0; k < n; ++k) {
    if (bvh.nodes[children[k]].is_leaf()) continue;
    uint32_t child_slot = uint32_t(wide.nodes.size());
    wide.nodes.push_back({});
    wide.nodes[slot].child[k] = child_slot;
    collapse(bvh, plan, children[k], child_slot, wide);
  }
}

}  // namespace

WideBvh collapse_to_wide(const Bvh& bvh) {
  WideBvh wide;
  if (bvh.empty()) return wide;
  wide.nodes.reserve(bvh.nodes.size() / 4 + 1);
  wide.nodes.push_back({});
  CollapsePlan plan;
  plan.best.resize(bvh.nodes.size());
  plan.take.resize(bvh.nodes.size());
  plan_subtree(bvh, 0, plan);
  collapse(bvh, plan, 0, 0, wide);
  return wide;
}

}  // namespace raylane
