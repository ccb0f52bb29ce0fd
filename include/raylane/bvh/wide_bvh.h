// The BVH collapsed to 8-wide nodes, for single-ray traversal that tests one ray against
// eight child boxes in one SIMD step (Wald et al. 2008, "Getting Rid of Packets"; Fuetterling
// et al. 2017, "Accelerated Single Ray Tracing for Wide Vector Units"). Its leaves are the
// binary BVH's leaves: ranges of Bvh::refs, so both trees share the refs and the permuted
// tables, and a hit has the same PrimRef whichever tree found it.
#pragma once

#include <cstdint>
#include <vector>

namespace raylane {

struct Bvh;

inline constexpr int kWideArity = 8;

// 256 bytes: the children's boxes in SoA (one child per lane) and what each child is.
// Children fill slots [0, arity); an unused slot has an empty box (lo = +inf, hi = −inf),
// which a ray enters at t = +inf (traversal clamps tmax to FLT_MAX so that never passes).
struct alignas(64) WideNode {
  // box[axis][0][k] = lo, box[axis][1][k] = hi of child k along axis; a ray's near plane is
  // box[axis][sign of d][...], its far plane box[axis][1 − sign][...].
  float box[3][2][kWideArity];
  // Inner child: its index in WideBvh::nodes. Leaf: if bit k of one_kind is set, the leaf
  // holds one kind, and this is the PrimRef bits of its first row (rows are contiguous, so
  // traversal needs no refs); otherwise the index of its first ref in Bvh::refs.
  uint32_t child[kWideArity];
  uint16_t count[kWideArity];  // 0: inner child or unused slot; > 0: a leaf of this many refs
  uint8_t arity;               // children in use, 1 … 8
  uint8_t one_kind;            // bit k: leaf child k holds rows of one kind
  uint8_t pad[14];

  bool is_leaf(int k) const { return count[k] > 0; }
  bool is_one_kind(int k) const { return (one_kind >> k) & 1; }
};
static_assert(sizeof(WideNode) == 256);

// Stacks over the wide tree (single rays, mixed packets) hold this many entries: a wide node pushes
// at most 7 of its children, and the tree is at most as deep as the binary one.
inline constexpr int kWideStackSize = 7 * 64 + 1;

struct WideBvh {
  std::vector<WideNode> nodes;  // nodes[0] is the root; empty when the BVH is

  bool empty() const { return nodes.empty(); }
  std::size_t bytes() const { return nodes.size() * sizeof(WideNode); }
};

// The 8-wide tree over `bvh`: each wide node holds a cut of at most 8 nodes of the binary
// subtree below a binary node, the cuts chosen for the least expected wide-node visits.
WideBvh collapse_to_wide(const Bvh& bvh);

}  // namespace raylane
