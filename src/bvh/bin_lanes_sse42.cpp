// The builder's loops (build_lanes.h) for SSE4.2, which every x86-64 raylane runs on: a box is
// two registers of four lanes (box_lanes.h), the SAH sweep four double pairs (sweep_lanes.h).
#include "bvh/box_lanes.h"
#include "bvh/build_lanes.h"
#include "bvh/sweep_lanes.h"

static_assert(XSIMD_WITH_SSE4_2, "this file must be compiled with SSE4.2");

namespace raylane::bvh_build {

namespace {
using A = xsimd::sse4_2;
}  // namespace

const BuildLanes kBuildLanesSse42 = {lanes::sweep_bins<A, A>, lanes::bound_records<A>,
                                     lanes::bin_records<A>, lanes::partition_records<A>};

}  // namespace raylane::bvh_build
