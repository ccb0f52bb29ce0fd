// The lane BSDF compiled for one instruction set (flags set in CMakeLists.txt).
#include "render/shade_lanes_impl.h"

static_assert(XSIMD_WITH_SSE4_2,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::detail {

void shade_lanes_sse42(const LaneMaterials& materials, ShadeBatch& batch) {
  shade_lanes_range<xsimd::sse4_2>(materials, batch);
}

}  // namespace raylane::detail
