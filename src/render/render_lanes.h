// The render's lane kernels, compiled once per instruction set (render_lanes_sse42.cpp,
// render_lanes_avx2.cpp, render_lanes_avx512.cpp, each from the same *_impl.h sources) into one
// table of entry points each: the BSDF, the Sobol groups, the light points (spheres' cones, points
// by area on boxes, cylinders and triangles), what follows the BSDF, both at once with the queues'
// write-back (the scatter kernel), the pinhole's camera rays, the arrivals' sort and the live
// blocks' bits. The public functions (shade_lanes, sobol_groups, sample_cones, sample_box_faces,
// sample_area_lights, finish_vertices, scatter_vertices, pinhole_rays, sort_arrival_rows,
// blocks_of_paths) look their kernel up here, the one place an instruction set
// picks one (as bvh/build_lanes.h does for the builder). This header has no xsimd.
#pragma once

#include <cstddef>
#include <cstdint>

#include "raylane/render/arrival_lanes.h"
#include "raylane/render/camera/camera_lanes.h"
#include "raylane/render/lights/light_lanes.h"
#include "raylane/render/materials/shade_lanes.h"
#include "raylane/render/samplers/sobol.h"
#include "raylane/render/vertex_lanes.h"
#include "raylane/simd/isa.h"

namespace raylane::detail {

struct RenderLanes {
  // shade_lanes (render/materials/shade_lanes.h).
  void (*shade)(const LaneMaterials& materials, ShadeBatch& batch);
  // sobol_groups (render/samplers/sobol.h) for the bit-reversed index, components `which` (0 and 1
  // among them), and their numbers into the callers' columns.
  void (*sobol_groups)(uint32_t reversed_index, uint32_t group, unsigned which, SobolBatch& batch,
                       const SobolNumbers& numbers);
  // sample_cones (render/lights/light_lanes.h).
  void (*sample_cones)(ConeBatch& batch, const ConeSphere* every_row);
  // sample_box_faces (render/lights/light_lanes.h).
  void (*sample_box_faces)(ConeBatch& batch, const double* u_part, const ConeBox& box);
  // sample_area_lights (render/lights/light_lanes.h).
  void (*sample_area_lights)(ConeBatch& batch, const double* u_part, const AreaLightRows& rows,
                             const AreaLightTables& tables);
  // finish_vertices (render/vertex_lanes.h).
  void (*finish_vertices)(const VertexRules& rules, const ShadeBatch& bsdf,
                          const LightQueries* lights, VertexBatch& batch);
  // scatter_vertices (render/vertex_lanes.h).
  void (*scatter_vertices)(const LaneMaterials& materials, const VertexRules& rules,
                           ShadeBatch& bsdf, const LightQueries* lights, VertexBatch& batch,
                           VertexQueues& queues);
  // gather_wo (render/vertex_lanes.h).
  void (*gather_wo)(const RayStream& rays, const uint32_t* rows, std::size_t n, ShadeBatch& shade);
  // pinhole_rays (render/camera/camera_lanes.h) for the points [0, the count rounded down to the
  // lane width): returns that count.
  std::size_t (*pinhole_rays)(const Camera& cam, const PixelPoints& points, RayStream& out);
  // sort_arrival_rows (render/arrival_lanes.h).
  void (*sort_arrivals)(const ArrivalColumns& in, ArrivalRows& out);
  // blocks_of_paths (render/path_blocks.h).
  uint64_t (*blocks_of_paths)(const uint32_t* path, std::size_t n, unsigned shift);
};

extern const RenderLanes kRenderLanesSse42, kRenderLanesAvx2, kRenderLanesAvx512;

// The kernels for `isa`, which the CPU must support (isa_supported).
const RenderLanes& render_lanes(Isa isa);

// sobol_groups (render/samplers/sobol.h) and pinhole_rays (render/camera/camera_lanes.h) with
// the kernels already chosen: the render's thread context holds its table, looked up once per
// render (LaneShading::kernels), and calls these; the public functions look the table up for
// their Isa and call them.
void sobol_groups(const RenderLanes& lanes, uint32_t index, uint32_t group, SobolBatch& batch,
                  unsigned components = kAllComponents, const SobolNumbers& numbers = {});
void pinhole_rays(const RenderLanes& lanes, const Camera& cam, const PixelPoints& points,
                  RayStream& out);

}  // namespace raylane::detail
