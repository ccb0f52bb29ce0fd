// The builder's loops over records and bins, compiled once per instruction set
// (bin_lanes_sse42.cpp, bin_lanes_avx2.cpp, bin_lanes_avx512.cpp) like the packet tracer's,
// and chosen at run time. This header has no xsimd: the builder calls them through the table.
// Every instruction set computes the same numbers (the same float and double operations on
// the same values, lane for lane), so the tree does not depend on the CPU.
#pragma once

#include "bvh/sah_split.h"
#include "raylane/simd/isa.h"

namespace raylane::bvh_build {

struct BuildLanes {
  // best_split (sah_split.h) given the parent's half area (at least 1e-300).
  Split (*sweep)(const BinSet& bins, const BinGrid& grid, double parent_area,
                 double traversal_cost);
  // Extends `bounds` by prims [0, n).
  void (*bound)(const BuildPrim* prims, uint32_t n, NodeBounds& bounds);
  // Adds prims [0, n) to the bins of `grid` (the bins were cleared by the caller).
  void (*bin)(const BuildPrim* prims, uint32_t n, const BinGrid& grid, BinSet& bins);
  // Reorders prims [0, n) in place so that those whose bin on `axis` is ≤ `last_left_bin` come
  // first; returns their number and extends `left` and `right` by the bounds of each side.
  uint32_t (*partition)(BuildPrim* prims, uint32_t n, const BinGrid& grid, int axis,
                        int last_left_bin, NodeBounds& left, NodeBounds& right);
};

extern const BuildLanes kBuildLanesSse42, kBuildLanesAvx2, kBuildLanesAvx512;

// The loops for `isa`, which the CPU must support (isa_supported).
const BuildLanes& build_lanes(Isa isa);

}  // namespace raylane::bvh_build
