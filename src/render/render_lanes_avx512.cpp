// The render's lane kernels (render/render_lanes.h) compiled for one instruction set (flags set in
// CMakeLists.txt).
#include "render/render_lanes_impl.h"

static_assert(XSIMD_WITH_AVX512BW,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::detail {

const RenderLanes kRenderLanesAvx512 = render_lanes_for<xsimd::avx512bw>();

}  // namespace raylane::detail
