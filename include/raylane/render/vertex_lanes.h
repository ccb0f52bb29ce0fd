// What a wavefront's vertices do after their BSDF (docs/design.md, "The scatter kernel"), in float
// SIMD lanes: the contribution and origin of each vertex's shadow ray toward its light point, and
// its next throughput (Russian roulette included) and ray origin, offset by the point's error
// bound (VertexBatch::p_error, the kind's own: SurfaceColumns). The steps are written once over
// the number type (render/vertex_steps.h; core/ray_offset.h's offset_origin and shadow_tmax):
// the double shading takes them at double, the lanes at float lanes,
// and their scalar float instance is the lanes' bit-for-bit reference
// (tests/render/vertex_lanes_test.cpp). scatter_vertices runs the BSDF (shade_lanes.h) and these
// steps in one pass over the rows, the BSDF's answers kept in registers.
//
// Baseline code includes this header; the kernel lives in the per-ISA translation units
// src/render/render_lanes_<isa>.cpp, picked at run time through their table
// (src/render/render_lanes.h).
#pragma once

#include <array>
#include <cassert>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "raylane/core/vec_math.h"
#include "raylane/render/lights/lights.h"
#include "raylane/render/materials/shade_lanes.h"
#include "raylane/render/vertex_steps.h"
#include "raylane/simd/isa.h"
#include "raylane/trace/ray_stream.h"

namespace raylane {

// Fill rows [0, size) after resize(), run scatter_vertices() (or finish_vertices()), read the
// outputs. Rows past size up to the lane width are padding the kernel computes and nobody reads.
struct VertexBatch {
  using Column = std::vector<float>;
  using Columns3 = std::array<Column, 3>;
  // Inputs. The vertex: the path's throughput, the float hit point with its componentwise
  // error bound (SurfaceColumns) and geometric normal, and roulette's number. The light point
  // and the BSDF's answers are read where their steps left them. Roulette's survival
  // probability per row (VertexRules::roulette): 1 for a row without roulette, which then
  // always survives (u < 1) with its throughput unchanged (x / 1 is x).
  Columns3 beta, p, p_error, ng;
  Column u_roulette, survival;
  // Outputs. The shadow ray (shadow_ok 1 where one is cast): what it adds if it sees the
  // light, widened to double for the shadow queue.
  std::array<std::vector<double>, 3> shadow_c;
  Column shadow_ok;
  // The next ray (alive 1 where the path goes on): the new throughput.
  Columns3 next_beta;
  Column alive;
  // Where the shadow ray and the next ray start, and where the shadow ray ends.
  Columns3 shadow_o, next_o;
  Column shadow_tmax;

  std::size_t size() const { return size_; }
  // Rows [0, n), padded to a multiple of 16 lanes. Rows below n keep their values; the columns
  // never shrink.
  void resize(std::size_t n);

 private:
  std::size_t size_ = 0;
};

// The rows' rays' directions turned around, for the BSDF: row r's is the stream's ray rows[r]
// (r < n), into shade.wo bit for bit. The batch must have room for n rows (resize).
void gather_wo(Isa isa, const RayStream& rays, const uint32_t* rows, std::size_t n,
               ShadeBatch& shade);

struct VertexRules {
  bool mis = false;       // weigh the shadow ray by the power heuristic (else 1)
  bool roulette = false;  // Russian roulette at this depth (the lanes: at some rows)
  double survival = 1;    // roulette's survival probability (the lanes: the survival column)
};

// The batch's shadow rays and next rays. Row r's light point is row r of `lights` (le,
// cones.dist and cones.pdf, rounded to float, and bsdf.light_wi; a pdf not above 0: none), or
// none for every row without `lights`; its BSDF's answers are row r of `bsdf` (sample: wi,
// value, pdf; at the light point: light_f, light_pdf). Both are read as their steps left them,
// padded at least as far as `batch`.
void finish_vertices(Isa isa, const VertexRules& rules, const ShadeBatch& bsdf,
                     const LightQueries* lights, VertexBatch& batch);

// Where the scatter kernel queues its rows' rays, each queue in row order from its
// destinations' first element: the next rays (origin, direction and path) of the rows that go
// on, finish_vertices' rows with `alive`, and the shadow rays (origin, direction toward the light
// point, end, light, path and contribution) of the rows that cast one, its rows with
// `shadow_ok`. Every destination needs room for the batch's rows rounded up to 16: the lanes
// store whole registers, and what lies past the queued rows is overwritten; `path` and `depth`
// are read so too. Without lights the shadow destinations are not written and may be null. The
// caller fills what the kernel does not: the rays' tmin and tmax, the next rays' specular flag
// (0: lanes shade no Dirac lobe).
struct VertexQueues {
  const uint32_t* path = nullptr;   // row r's path, into both queues
  const uint32_t* depth = nullptr;  // row r's depth; its next ray's is one more
  std::array<float*, 3> next_o{}, next_d{};
  uint32_t* next_path = nullptr;
  // What the next ray carries of its path (render/wavefront/queues.h, PathCarry): the new
  // throughput, the vertex it leaves and the BSDF's density, its depth.
  std::array<double*, 3> next_beta{};
  std::array<float*, 3> next_prev_p{};
  double* next_prev_pdf = nullptr;
  uint32_t* next_depth = nullptr;
  std::array<float*, 3> shadow_o{}, shadow_d{};
  float* shadow_tmax = nullptr;
  uint32_t* shadow_light = nullptr;  // the row's light (LightQueries::light_of), as its bits
  uint32_t* shadow_path = nullptr;
  std::array<double*, 3> shadow_c{};
  // The kernel's answers: how many rows each queue took.
  std::size_t next_count = 0, shadow_count = 0;
};

// shade_lanes and finish_vertices in one pass over the rows (the scatter kernel): the BSDF's
// sample and at once the steps after it, and their rays straight into the queues with what
// they carry of their paths, the rows that cast none dropped as they go (a filter over
// finish_vertices' columns, fused). The BSDF's and finish_vertices' own columns are not stored:
// what a row hands on is in its rays.
void scatter_vertices(Isa isa, const LaneMaterials& materials, const VertexRules& rules,
                      ShadeBatch& bsdf, const LightQueries* lights, VertexBatch& batch,
                      VertexQueues& queues);

// The steps for one vertex, at double for the double shading and at float as the lanes' scalar
// twin (T double or float). The ray origins are offset_origin<T>(p, error, ng, direction), the
// shadow ray's end shadow_tmax<T>(origin, p, light_wi, light_dist) (core/ray_offset.h), with
// error hit_point_error in double and the row's p_error in float.
//
// A shadow ray's contribution if it sees the light, beta·f·Le·(w / light_pdf) with w the power
// heuristic under MIS: false when it has none (no light point, f = 0, or not finite).
template <class T>
bool shadow_contribution(const VertexRules& rules, const glm::vec<3, T>& beta,
                         const glm::vec<3, T>& f, const glm::vec<3, T>& le, T light_pdf, T bsdf_pdf,
                         glm::vec<3, T>& c) {
  if (!(light_pdf > 0) || f == glm::vec<3, T>(0)) return false;
  c = shadow_ray_contribution<T>(rules.mis, beta, f, le, light_pdf, bsdf_pdf);
  return is_finite(c);
}
// The throughput after the BSDF's sample, beta·value / pdf, and Russian roulette: false when
// the path ends (no sample, roulette, or a zero or non-finite throughput).
template <class T>
bool next_throughput(const VertexRules& rules, const glm::vec<3, T>& beta,
                     const glm::vec<3, T>& value, T pdf, T u_roulette, glm::vec<3, T>& next) {
  if (!(pdf > 0)) return false;
  next = sampled_throughput<T>(beta, value, pdf);
  if (rules.roulette) {
    const T survival = T(rules.survival);
    if (u_roulette >= survival) return false;
    next = survivor_throughput<T>(next, survival);
  }
  return is_finite(next) && next != glm::vec<3, T>(0);
}

}  // namespace raylane
