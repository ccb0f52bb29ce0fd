#include "render/render_lanes.h"

namespace raylane::detail {

const RenderLanes& render_lanes(Isa isa) {
  return for_isa(isa, kRenderLanesSse42, kRenderLanesAvx2, kRenderLanesAvx512);
}

}  // namespace raylane::detail

namespace raylane {

void sort_arrival_rows(Isa isa, const ArrivalColumns& in, ArrivalRows& out) {
  detail::render_lanes(isa).sort_arrivals(in, out);
}

}  // namespace raylane
