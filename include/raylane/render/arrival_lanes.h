// Where a wavefront's rays arrived, sorted in SIMD lanes (the path tracer's arrival stage,
// src/render/wavefront/arrival.cpp): each ray's hit, its material and the material's route, and
// its path's depth decide whether the hit is a vertex shaded in lanes, a rarer case that scalar
// code finishes (an escape under an environment, an emitter, a vertex shaded in double), or the
// end of the path (a miss without an environment, a path at its last bounce). The lane rows
// take what their rays carry of their paths (the depth, the throughput) as they are packed,
// then their Sobol seeds and roulette's survival from their paths and depths. A batch
// of rays is classified at once and its lane rows packed into their columns; a row by row loop paid
// a branch chain and a queue's push per ray.
//
// Baseline code includes this header; the kernel lives in the per-ISA translation units
// src/render/render_lanes_<isa>.cpp, picked at run time through their table
// (src/render/render_lanes.h).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "raylane/prims/prim_list.h"
#include "raylane/scene/scene.h"
#include "raylane/simd/isa.h"

namespace raylane {

// What the kernel reads: rays [0, count) of a wavefront.
struct ArrivalColumns {
  const uint32_t* prim = nullptr;      // ray k's hit (PrimRef bits; kInvalidBits for a miss)
  const uint32_t* ray_path = nullptr;  // ray k's path
  std::size_t count = 0;
  // What ray k carries of its path: the depth it arrives at, the throughput.
  const uint32_t* depth = nullptr;
  std::array<const double*, 3> beta{};
  // Each kind's material column (the scene's tables) and the column's length (a CSG table's
  // counts leaves, not blocks), by PrimTag; null for a kind no hit can have (an empty table).
  std::array<const uint32_t*, kPrimKindCount> material_of{};
  std::array<std::size_t, kPrimKindCount> rows_of{};
  // Material m's route (LaneMaterials::Route as an integer): route[m], m < materials.
  const uint32_t* route = nullptr;
  std::size_t materials = 0;
  uint32_t emitter_route = 0;  // the route of emitters
  uint32_t lanes_route = 0;    // the route shaded in lanes (one no material has: none)
  uint32_t max_depth = 0;      // a path at this depth sends no ray on (depths below 2^31)
  bool environment = false;    // whether an escape sees something
  // For the lane rows' columns from their paths and depths (row_path_columns_of; none where
  // pixel_seed is null): path p's pixel seed at pixel_seed[p · seed_stride] (p · seed_stride
  // below 2^31); a row's light group salt light_salt + depth · salt_step and its BSDF group's
  // that plus bsdf_offset, modulo 2^64 (group_salt of render/samplers/sobol.h is linear in the
  // group, and the groups in the depth); roulette's survival from depth roulette_from on
  // (below 2^31), else 1.
  const uint64_t* pixel_seed = nullptr;
  uint32_t seed_stride = 1;
  uint64_t light_salt = 0, salt_step = 0, bsdf_offset = 0;
  uint32_t roulette_from = 0;
  float survival = 1;
};

// What it writes. The lane rows' columns and the rare rows need room for count rows rounded up
// to 16 (whole registers are stored).
struct ArrivalRows {
  // The vertices shaded in lanes, in ray order: path, ray, material, depth, and the throughput
  // rounded to float.
  uint32_t *path = nullptr, *ray = nullptr, *material = nullptr, *depth = nullptr;
  std::array<float*, 3> beta{};
  std::size_t lanes = 0;
  // The rays whose arrival scalar code finishes, in order: escapes under an environment,
  // emitters, and vertices shaded in double (not at the last bounce).
  uint32_t* rare = nullptr;
  std::size_t rare_count = 0;
  // The lane rows' Sobol seeds for their light and BSDF groups and roulette's survival, and
  // whether any row has roulette (where ArrivalColumns::pixel_seed is set).
  uint64_t *light_seed = nullptr, *bsdf_seed = nullptr;
  float* survival = nullptr;
  bool any_roulette = false;
};

// The reference: sort_arrival_rows' answer for ray k, one ray at a time.
enum class Arrival { kEnd, kLanes, kRare };
inline Arrival arrival_of(const ArrivalColumns& in, std::size_t k) {
  const PrimRef hit = PrimRef::from_bits(in.prim[k]);
  if (!hit.valid()) return in.environment ? Arrival::kRare : Arrival::kEnd;
  const uint32_t route = in.route[in.material_of[std::size_t(hit.tag())][hit.row()]];
  if (route == in.emitter_route) return Arrival::kRare;
  if (in.depth[k] >= in.max_depth) return Arrival::kEnd;
  return route == in.lanes_route ? Arrival::kLanes : Arrival::kRare;
}

// Sorts rays [0, in.count) into out's lane rows and rare rows (both from 0).
void sort_arrival_rows(Isa isa, const ArrivalColumns& in, ArrivalRows& out);

// The material columns of `scene`'s kinds into in.material_of and in.rows_of (none for an
// empty table): a hit's material is then Scene::material_of's.
void set_material_columns(const Scene& scene, ArrivalColumns& in);

// Lane row r's columns from its path and depth (out.path[r], out.depth[r]), one row at a time:
// the lanes' reference. Returns whether the row has roulette.
inline bool row_path_columns_of(const ArrivalColumns& in, const ArrivalRows& out, std::size_t r) {
  const uint64_t seed = in.pixel_seed[std::size_t(out.path[r]) * in.seed_stride];
  const uint64_t light = in.light_salt + uint64_t(out.depth[r]) * in.salt_step;
  out.light_seed[r] = seed ^ light;
  out.bsdf_seed[r] = seed ^ (light + in.bsdf_offset);
  const bool roulette = out.depth[r] >= in.roulette_from;
  out.survival[r] = roulette ? in.survival : 1.0f;
  return roulette;
}

}  // namespace raylane
