// The steps around the builder (build.cpp): its records gathered from the scene's tables, and
// the finished tree, refs and tables handed to the Bvh.
#pragma once

#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

#include "bvh/build_prim.h"
#include "raylane/bvh/bvh.h"

namespace raylane {
struct Scene;
}

namespace raylane::bvh_build {

struct FreeMalloc {
  void operator()(void* p) const { std::free(p); }
};
template <class T>
using MallocPtr = std::unique_ptr<T, FreeMalloc>;

// n zeroed bytes: calloc, whose large blocks are fresh pages the kernel zeroes when first
// touched, so the bytes never written cost nothing.
inline MallocPtr<uint8_t> allocate_zeroed_bytes(std::size_t n) {
  MallocPtr<uint8_t> p(static_cast<uint8_t*>(std::calloc(n > 0 ? n : 1, 1)));
  if (!p) throw std::bad_alloc();
  return p;
}

// Room for n objects of an aggregate T (their lifetimes begin when written), neither zeroed
// nor touched: a page costs nothing until the first object on it is written, by whichever
// thread writes it. Aligned to a cache line, so that no 32-byte record or node straddles two
// (the binning loads a record as one 32-byte row: box_lanes.h).
template <class T>
MallocPtr<T> allocate_unwritten(std::size_t n) {
  constexpr std::size_t kLine = 64;
  const std::size_t bytes = (sizeof(T) * (n > 0 ? n : 1) + kLine - 1) / kLine * kLine;
  MallocPtr<T> p(static_cast<T*>(std::aligned_alloc(kLine, bytes)));
  if (!p) throw std::bad_alloc();
  return p;
}

// One record per primitive of every kind, kinds in PrimKinds order; large tables are read by
// `threads` threads.
MallocPtr<BuildPrim> gather(const Scene& scene, int threads);

// Copies the tree whose root is slots[0] (Pending in build.cpp: a node's children are the two
// slots its index names, and its flags byte holds its depth) to `out`: the slots whose `used` flag
// is 1, in slot order, which is depth first (each node's children adjacent, placed when their
// parent is, the left subtree's pairs before the right's), child indices renumbered and flags
// zeroed. The result, and the statistics summed along the way (`stats`: counts, depth, leaf
// sizes, SAH cost), are the same for any number of `threads`. `slot_count` flags are read;
// `prims` gives the leaves' refs.
void compact_tree(const BvhNode* slots, const uint8_t* used, uint32_t slot_count,
                  const BuildPrim* prims, double traversal_cost, int threads,
                  std::vector<BvhNode>& out, BvhStats& stats);

// The refs of prims [0, n), in order.
std::vector<PrimRef> take_refs(const BuildPrim* prims, uint32_t n, int threads);

// Reorders every table into leaf order (Scene::permute) and rewrites the refs to the new rows;
// returns, per kind, the old row of each new row.
std::vector<std::vector<uint32_t>> permute_scene(Scene& scene, std::vector<PrimRef>& refs);

// Points each leaf of one kind at its first row (BvhNode::kOneKind; `refs` permuted: its rows
// are contiguous) and each other leaf at its refs in the returned array, the mixed leaves' refs
// in node order, the same for any number of `threads`.
std::vector<PrimRef> index_leaves(std::vector<BvhNode>& nodes, const std::vector<PrimRef>& refs,
                                  int threads);

}  // namespace raylane::bvh_build
