// The render loop's lanes compiled for one instruction set (flags set in CMakeLists.txt): the
// BSDF, the Sobol groups, the sphere lights' cones, what follows the BSDF and the pinhole's
// camera rays.
#include "render/camera_lanes_impl.h"
#include "render/light_lanes_impl.h"
#include "render/shade_lanes_impl.h"
#include "render/sobol_lanes_impl.h"
#include "render/vertex_lanes_impl.h"

static_assert(XSIMD_WITH_AVX512BW,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::detail {

void shade_lanes_avx512(const LaneMaterials& materials, ShadeBatch& batch) {
  shade_lanes_range<xsimd::avx512bw>(materials, batch);
}

void sobol_groups_avx512(uint32_t reversed_index, uint32_t group, unsigned which, SobolBatch& batch,
                         const SobolNumbers& numbers) {
  sobol_groups_range<xsimd::avx512bw>(reversed_index, group, which, batch);
  sobol_numbers<xsimd::avx512bw>(which, batch, numbers);
}

void sample_cones_avx512(ConeBatch& batch) {
  sample_cones_range<xsimd::avx512bw>(batch);
}

void finish_vertices_avx512(const VertexRules& rules, const ShadeBatch& bsdf,
                            const LightQueries* lights, VertexBatch& batch) {
  finish_vertices_range<xsimd::avx512bw>(rules, bsdf, lights, batch);
}

std::size_t filter_rows_avx512(const RowFilter& filter, std::size_t rows) {
  return filter_rows_range<xsimd::avx512bw>(filter, rows);
}

std::size_t pinhole_rays_avx512(const Camera& cam, const PixelPoints& points, RayStream& out) {
  return pinhole_rays_range<xsimd::avx512bw>(cam, points, out);
}

}  // namespace raylane::detail
