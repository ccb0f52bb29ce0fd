// The builder's loops over records and bins, compiled once per instruction set
// (bin_lanes_sse42.cpp, bin_lanes_avx2.cpp, bin_lanes_avx512.cpp) like the packet tracer's,
// and chosen at run time. This header has no xsimd: the builder calls them through the table.
#pragma once

#include "bvh/sah_split.h"
#include "raylane/simd/isa.h"

namespace raylane::bvh_build {

struct BuildLanes {
  // best_split (sah_split.h) given the parent's half area (at least 1e-300).
  Split (*sweep)(const BinSet& bins, const BinGrid& grid, double parent_area,
                 double traversal_cost);
};

extern const BuildLanes kBuildLanesSse42, kBuildLanesAvx2, kBuildLanesAvx512;

// The loops for `isa`, which the CPU must support (isa_supported).
const BuildLanes& build_lanes(Isa isa);

}  // namespace raylane::bvh_build
