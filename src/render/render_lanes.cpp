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

void set_material_columns(const Scene& scene, ArrivalColumns& in) {
  PrimKinds::for_each([&](auto kind) {
    const auto& table = scene.table<decltype(kind)>();
    const std::size_t t = kind_index<decltype(kind)>();
    in.material_of[t] = nullptr, in.rows_of[t] = 0;
    if (table.size() == 0) return;
    // The column's own length: a CSG table's counts leaves (a hit names its leaf), not blocks.
    in.material_of[t] = table.material.data(), in.rows_of[t] = table.material.size();
  });
}

uint64_t blocks_of_paths(Isa isa, const uint32_t* path, std::size_t n, unsigned shift) {
  return detail::render_lanes(isa).blocks_of_paths(path, n, shift);
}

}  // namespace raylane
