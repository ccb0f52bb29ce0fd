// The builder's loops (build_lanes.h) compiled for AVX2 (flags set in CMakeLists.txt).
#include "bvh/build_lanes.h"
#include "bvh/sweep_lanes.h"

static_assert(XSIMD_WITH_FMA3_AVX2,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::bvh_build {

const BuildLanes kBuildLanesAvx2 = {lanes::sweep_bins<xsimd::fma3<xsimd::avx2>>};

}  // namespace raylane::bvh_build
