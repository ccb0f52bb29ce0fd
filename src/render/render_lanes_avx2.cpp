// The render's lane kernels (render/render_lanes.h) compiled for one instruction set (flags set in
// CMakeLists.txt).
#include "render/camera_lanes_impl.h"
#include "render/light_lanes_impl.h"
#include "render/render_lanes.h"
#include "render/shade_lanes_impl.h"
#include "render/sobol_lanes_impl.h"
#include "render/vertex_lanes_impl.h"

static_assert(XSIMD_WITH_FMA3_AVX2,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::detail {

namespace {

using A = xsimd::fma3<xsimd::avx2>;

void sobol_groups_and_numbers(uint32_t reversed_index, uint32_t group, unsigned which,
                              SobolBatch& batch, const SobolNumbers& numbers) {
  sobol_groups_range<A>(reversed_index, group, which, batch);
  sobol_numbers<A>(which, batch, numbers);
}

}  // namespace

const RenderLanes kRenderLanesAvx2 = {shade_lanes_range<A>,  sobol_groups_and_numbers,
                                      sample_cones_range<A>, finish_vertices_range<A>,
                                      filter_rows_range<A>,  pinhole_rays_range<A>};

}  // namespace raylane::detail
