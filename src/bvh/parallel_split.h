// Binning and partitioning one large node with every thread: the top levels of a build, where
// there are too few subtrees to keep the threads busy. The node's prims are cut into `parts`
// contiguous chunks, one OpenMP task each (its own bins, then its own in-place partition), so
// a thread that a busy core delays holds up at most one chunk. Call these from inside a
// parallel region before any subtree task exists: binning in tasks while subtree tasks were
// queued made 2-thread builds 1.3–1.6× slower (a thread waiting for its bins picked up a
// whole subtree first; bench/README.md). Outside a parallel region they run serially.
#pragma once

#include "bvh/build_lanes.h"

namespace raylane::bvh_build {

// The bins of prims [0, n), by `lanes` (`bins` is cleared here).
void bin_in_parallel(const BuildLanes& lanes, const BuildPrim* prims, uint32_t n,
                     const BinGrid& grid, int parts, BinSet& bins);

// lanes.partition over prims [0, n): each chunk is partitioned in place, then the right-side
// prims left of the final middle swap places with the left-side prims right of it. Returns
// the number that go left; `left` and `right` are set to the bounds of each side.
uint32_t partition_in_parallel(const BuildLanes& lanes, BuildPrim* prims, uint32_t n,
                               const BinGrid& grid, int axis, int last_left_bin, int parts,
                               NodeBounds& left, NodeBounds& right);

// The bounds of prims [0, n).
NodeBounds bound_in_parallel(const BuildLanes& lanes, const BuildPrim* prims, uint32_t n,
                             int parts);

}  // namespace raylane::bvh_build
