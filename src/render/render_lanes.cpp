#include "render/render_lanes.h"

namespace raylane::detail {

const RenderLanes& render_lanes(Isa isa) {
  switch (isa) {
    case Isa::kAvx512:
      return kRenderLanesAvx512;
    case Isa::kAvx2:
      return kRenderLanesAvx2;
    case Isa::kSse42:
      break;
  }
  return kRenderLanesSse42;
}

}  // namespace raylane::detail
