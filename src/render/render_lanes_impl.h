// The table of render kernels (render/render_lanes.h) for one instruction set A: the one source
// that render_lanes_sse42.cpp, render_lanes_avx2.cpp and render_lanes_avx512.cpp each compile
// with their own flags. Include from those files only.
#pragma once

#include "render/arrival_lanes_impl.h"
#include "render/blocks_lanes_impl.h"
#include "render/camera/camera_lanes_impl.h"
#include "render/lights/light_lanes_impl.h"
#include "render/materials/shade_lanes_impl.h"
#include "render/render_lanes.h"
#include "render/samplers/sobol_lanes_impl.h"
#include "render/vertex_lanes_impl.h"

namespace raylane::detail {

template <class A>
void sobol_groups_and_numbers(uint32_t reversed_index, uint32_t group, unsigned which,
                              SobolBatch& batch, const SobolNumbers& numbers) {
  sobol_groups_range<A>(reversed_index, group, which, batch);
  sobol_numbers<A>(which, batch, numbers);
}

template <class A>
constexpr RenderLanes render_lanes_for() {
  return {shade_lanes_range<A>,       sobol_groups_and_numbers<A>, sample_cones_range<A>,
          sample_box_faces_range<A>,  sample_area_lights_range<A>, finish_vertices_range<A>,
          scatter_range<A>,           gather_wo_range<A>,          pinhole_rays_range<A>,
          sort_arrival_rows_range<A>, blocks_of_paths_range<A>};
}

}  // namespace raylane::detail
