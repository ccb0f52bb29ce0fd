// The builder's loops (build_lanes.h) compiled for AVX2 (flags set in CMakeLists.txt): a box is
// one register of eight float lanes (box_lanes.h).
#include "bvh/box_lanes.h"
#include "bvh/build_lanes.h"
#include "bvh/sweep_lanes.h"

static_assert(XSIMD_WITH_FMA3_AVX2,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::bvh_build {

namespace {
using A = xsimd::fma3<xsimd::avx2>;
}  // namespace

const BuildLanes kBuildLanesAvx2 = {lanes::sweep_bins<A, A>, lanes::bound_records<A>,
                                    lanes::bin_records<A>, lanes::partition_records<A>};

}  // namespace raylane::bvh_build
