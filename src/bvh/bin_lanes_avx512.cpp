// The builder's loops (build_lanes.h) compiled for AVX-512 (flags set in CMakeLists.txt).
#include "bvh/build_lanes.h"
#include "bvh/sweep_lanes.h"

static_assert(XSIMD_WITH_AVX512BW,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::bvh_build {

const BuildLanes kBuildLanesAvx512 = {lanes::sweep_bins<xsimd::avx512bw>};

}  // namespace raylane::bvh_build
