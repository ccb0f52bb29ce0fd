// The builder's loops (build_lanes.h) compiled for AVX-512 (flags set in CMakeLists.txt). A box
// is eight float lanes, as with AVX2 (box_lanes.h: sixteen would hold two records, but each
// updates bins of its own); the SAH sweep's eight double lanes are one register.
#include "bvh/box_lanes.h"
#include "bvh/build_lanes.h"
#include "bvh/sweep_lanes.h"

static_assert(XSIMD_WITH_AVX512BW,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::bvh_build {

namespace {
using A = xsimd::avx512bw;
using Box = xsimd::fma3<xsimd::avx2>;  // eight float lanes
}  // namespace

const BuildLanes kBuildLanesAvx512 = {lanes::sweep_bins<A, Box>, lanes::bound_records<Box>,
                                      lanes::bin_records<Box>, lanes::partition_records<Box>};

}  // namespace raylane::bvh_build
