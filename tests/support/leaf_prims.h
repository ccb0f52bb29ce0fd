// A BVH leaf's primitives, read from the leaf as its layout states (bvh/bvh.h), independently
// of the traversal's for_each_run: a leaf of one kind names its first row and its rows follow;
// any other leaf names its first ref in Bvh::refs.
#pragma once

#include <vector>

#include "raylane/bvh/bvh.h"

namespace raylane::testing {

inline std::vector<PrimRef> leaf_prims(const Bvh& bvh, const BvhNode& leaf) {
  std::vector<PrimRef> prims;
  for (uint32_t i = 0; i < leaf.count; ++i) {
    if (leaf.is_one_kind()) {
      PrimRef first = PrimRef::from_bits(leaf.index);
      prims.push_back(PrimRef(first.tag(), first.row() + i));
    } else {
      prims.push_back(bvh.refs.at(leaf.index + i));
    }
  }
  return prims;
}

}  // namespace raylane::testing
