#include "render/render_lanes.h"

#include "raylane/render/path_blocks.h"

namespace raylane::detail {

const RenderLanes& render_lanes(Isa isa) {
  return for_isa(isa, kRenderLanesSse42, kRenderLanesAvx2, kRenderLanesAvx512);
}

}  // namespace raylane::detail

namespace raylane {

void sort_arrival_rows(Isa isa, const ArrivalColumns& in, ArrivalRows& out) {
  detail::render_lanes(isa).sort_arrivals(in, out);
}

uint64_t blocks_of_paths(Isa isa, const uint32_t* path, std::size_t n, unsigned shift) {
  return detail::render_lanes(isa).blocks_of_paths(path, n, shift);
}

}  // namespace raylane
