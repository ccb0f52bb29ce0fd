// Choosing a node's split from its bins by the surface area heuristic (Wald 2007, "On fast
// Construction of SAH-based Bounding Volume Hierarchies", §3): the cost of a split is
// traversal_cost + (A_left·C_left + A_right·C_right) / A_parent, with C the summed test cost of
// a side's primitives.
#pragma once

#include "bvh/build_prim.h"
#include "raylane/bvh/bvh.h"
#include "raylane/simd/isa.h"

namespace raylane::bvh_build {

// Half the surface area, in double: float extents up to FLT_MAX would overflow a product.
double half_area(const Bounds3f& b);

struct Split {
  int axis = -1;      // -1: no split separates the centroids
  int last_left = 0;  // prims in bins [0, last_left] go left
  double cost = std::numeric_limits<double>::infinity();
};

// The grid of `bins` bins over the centroid bounds (BinGrid).
BinGrid make_grid(const NodeBounds& bounds, int bins);

// The cheapest split between bins on any axis whose centroids are not all equal, and that
// puts prims on both sides; the first such in the order of axes, then bins, on a tie. Swept
// in the lanes of `isa` (sweep_lanes.h), which the CPU must support; every ISA gives the same
// split and cost to the bit.
Split best_split(const BinSet& bins, const BinGrid& grid, const Bounds3f& box,
                 double traversal_cost, Isa isa);

// The summed test cost of every binned prim (the SAH cost of making the node a leaf).
double binned_cost(const BinSet& bins, int bin_count);

// True when making prims [0, n) a leaf is sure to cost no more than their best split, so
// binning them could only confirm it: each side of any split holds its prims' boxes, so the
// split costs at least traversal_cost + Σ c_i·A_i / A_parent (A_i a prim's half area). With a
// margin far above the rounding of either side, a true answer is the choice the bins would
// make; false says nothing.
bool leaf_by_bound(const BuildPrim* prims, uint32_t n, const Bounds3f& box, double traversal_cost);

}  // namespace raylane::bvh_build
