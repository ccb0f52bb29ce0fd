#include "render/render_lanes.h"

namespace raylane::detail {

const RenderLanes& render_lanes(Isa isa) {
  return for_isa(isa, kRenderLanesSse42, kRenderLanesAvx2, kRenderLanesAvx512);
}

}  // namespace raylane::detail
