// Collapsing the binary BVH into 8-wide nodes (the greedy surface-area rule of Wald et al.
// 2008, "Getting Rid of Packets", §3: open the largest child until the node is full).
#include <algorithm>
#include <limits>

#include "raylane/bvh/bvh.h"
#include "raylane/bvh/wide_bvh.h"

namespace raylane {

namespace {

double half_area(const BvhNode& n) {
  double dx = double(n.hi[0]) - n.lo[0], dy = double(n.hi[1]) - n.lo[1];
  double dz = double(n.hi[2]) - n.lo[2];
  return dx * dy + dy * dz + dz * dx;
}

// The binary nodes that become the children of one wide node: start from the two children
// of `inner` and open the inner child of largest area while there is room.
int gather_children(const Bvh& bvh, const BvhNode& inner, uint32_t (&out)[kWideArity]) {
  int n = 0;
  out[n++] = inner.index;
  out[n++] = inner.index + 1;
  while (n < kWideArity) {
    int best = -1;
    double best_area = -1;
    for (int k = 0; k < n; ++k) {
      const BvhNode& c = bvh.nodes[out[k]];
      if (!c.is_leaf() && half_area(c) > best_area) best = k, best_area = half_area(c);
    }
    if (best < 0) break;
    uint32_t opened = out[best];
    out[best] = bvh.nodes[opened].index;
    out[n++] = bvh.nodes[opened].index + 1;
  }
  return n;
}

void clear_slot(WideNode& w, int k) {
  const float inf = std::numeric_limits<float>::infinity();
  for (int axis = 0; axis < 3; ++axis)
    w.box[axis][0][k] = inf, w.box[axis][1][k] = -inf;
  w.child[k] = 0;
  w.count[k] = 0;
}

bool leaf_of_one_kind(const Bvh& bvh, const BvhNode& leaf) {
  PrimTag tag = bvh.refs[leaf.index].tag();
  for (uint32_t i = leaf.index + 1; i < leaf.index + leaf.count; ++i)
    if (bvh.refs[i].tag() != tag) return false;
  return true;
}

void set_slot(const Bvh& bvh, WideNode& w, int k, const BvhNode& b) {
  for (int axis = 0; axis < 3; ++axis)
    w.box[axis][0][k] = b.lo[axis], w.box[axis][1][k] = b.hi[axis];
  w.child[k] = b.index;  // a leaf's first ref; an inner child's index is set by the caller
  w.count[k] = b.count;
  if (b.is_leaf() && leaf_of_one_kind(bvh, b)) {
    w.child[k] = bvh.refs[b.index].bits();
    w.one_kind |= uint8_t(1u << k);
  }
}

// Makes the wide node for binary node `binary` at wide.nodes[slot], then its inner children,
// depth first.
void collapse(const Bvh& bvh, uint32_t binary, uint32_t slot, WideBvh& wide) {
  uint32_t children[kWideArity];
  const BvhNode& b = bvh.nodes[binary];
  int n = 1;
  if (b.is_leaf()) {
    children[0] = binary;  // a tree that is one leaf: a root with one child
  } else {
    n = gather_children(bvh, b, children);
  }
  WideNode w{};
  for (int k = 0; k < kWideArity; ++k) {
    if (k < n) {
      set_slot(bvh, w, k, bvh.nodes[children[k]]);
    } else {
      clear_slot(w, k);
    }
  }
  w.arity = uint8_t(n);
  wide.nodes[slot] = w;
  wide.of_binary[binary] = slot;
  for (int k = 0; k < n; ++k) {
    if (bvh.nodes[children[k]].is_leaf()) continue;
    uint32_t child_slot = uint32_t(wide.nodes.size());
    wide.nodes.push_back({});
    wide.nodes[slot].child[k] = child_slot;
    collapse(bvh, children[k], child_slot, wide);
  }
}

}  // namespace

WideBvh collapse_to_wide(const Bvh& bvh) {
  WideBvh wide;
  if (bvh.empty()) return wide;
  wide.nodes.reserve(bvh.nodes.size() / 4 + 1);
  wide.of_binary.assign(bvh.nodes.size(), WideBvh::kNone);
  wide.nodes.push_back({});
  collapse(bvh, 0, 0, wide);
  return wide;
}

}  // namespace raylane
