// The lane BSDF compiled for one instruction set (flags set in CMakeLists.txt).
#include "render/shade_lanes_impl.h"

static_assert(XSIMD_WITH_FMA3_AVX2,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::detail {

void shade_lanes_avx2(const LaneMaterials& materials, ShadeBatch& batch) {
  shade_lanes_range<xsimd::fma3<xsimd::avx2>>(materials, batch);
}

}  // namespace raylane::detail
