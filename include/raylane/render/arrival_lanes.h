// Where a wavefront's rays arrived, sorted in SIMD lanes (the path tracer's arrival stage,
// src/render/wavefront/arrival.cpp): each ray's hit, its material and the material's route, and
// its path's depth decide whether the hit is a vertex shaded in lanes, a rarer case that scalar
// code finishes (an escape under an environment, an emitter, a vertex shaded in double), or the
// end of the path (a miss without an environment, a path at its last bounce). The lane rows
// take what their rays carry of their paths (the depth, the throughput) as they are packed. A batch
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
  uint32_t max_depth = 0;      // a path at this depth sends no ray on
  bool environment = false;    // whether an escape sees something
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

// What the lane rows take from their paths and depths once they are sorted: each row's Sobol
// seeds for its light group and its BSDF group (its path's pixel seed salted by the group of its
// depth: light salt = light_salt + depth·salt_step, BSDF salt = light salt + bsdf_offset, all
// modulo 2^64, as group_salt of render/samplers/sobol.h gives them) and roulette's survival
// probability (`survival` from depth roulette_from on, else 1).
struct RowPathColumns {
  const uint32_t *path = nullptr, *depth = nullptr;
  std::size_t count = 0;
  const uint64_t* pixel_seed = nullptr;  // path p's at pixel_seed[p · seed_stride]
  uint32_t seed_stride = 1;
  uint64_t light_salt = 0, salt_step = 0, bsdf_offset = 0;
  uint32_t roulette_from = 0;
  float survival = 1;
  uint64_t *light_seed = nullptr, *bsdf_seed = nullptr;  // out
  float* survival_of_row = nullptr;                      // out
};

// Row r's columns, one row at a time: the lanes' reference. Returns whether it has roulette.
inline bool row_path_columns_of(const RowPathColumns& c, std::size_t r) {
  const uint64_t seed = c.pixel_seed[std::size_t(c.path[r]) * c.seed_stride];
  const uint64_t light = c.light_salt + uint64_t(c.depth[r]) * c.salt_step;
  c.light_seed[r] = seed ^ light;
  c.bsdf_seed[r] = seed ^ (light + c.bsdf_offset);
  const bool roulette = c.depth[r] >= c.roulette_from;
  c.survival_of_row[r] = roulette ? c.survival : 1.0f;
  return roulette;
}

// Every row's; returns whether any has roulette.
bool row_path_columns(Isa isa, const RowPathColumns& c);

}  // namespace raylane
