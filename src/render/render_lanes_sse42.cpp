// The render's lane kernels (render/render_lanes.h) compiled for one instruction set (flags set in
// CMakeLists.txt).
#include "render/render_lanes_impl.h"

static_assert(XSIMD_WITH_SSE4_2,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::detail {

const RenderLanes kRenderLanesSse42 = render_lanes_for<xsimd::sse4_2>();

}  // namespace raylane::detail
