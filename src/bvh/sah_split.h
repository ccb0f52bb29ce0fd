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

}  // namespace raylane::bvh_build
