// What a wavefront's vertices do after their BSDF (docs/design.md, "Shading in lanes"), in double
// SIMD lanes: the contribution and origin of each vertex's shadow ray toward its light point, and
// its next throughput (Russian roulette included) and ray origin. These are the path tracer's
// scalar steps (queue_shadow_ray, continue_path, offset_ray_origin, hit_point_error) in their order
// and precision, so the lanes give their answers bit for bit (tests/render/vertex_lanes_test.cpp)
// and the error analysis of the ray offsets (docs/hard-cases.md §5) is unchanged.
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
#include "raylane/simd/isa.h"
#include "raylane/trace/ray_stream.h"

namespace raylane {

// Fill rows [0, size) after resize(), run finish_vertices(), read the outputs. Rows past size
// up to the lane width are padding the kernel computes and nobody reads.
struct VertexBatch {
  using Column = std::vector<double>;
  using Columns3 = std::array<Column, 3>;
  using FloatColumn = std::vector<float>;
  using FloatColumns3 = std::array<FloatColumn, 3>;
  // Inputs. The vertex: the path's throughput, the hit point and geometric normal, the ray that
  // found it with its t (for the bound on the point's error), and roulette's number. The light
  // point and the BSDF's answers are read where their steps left them (finish_vertices).
  // Roulette's survival probability per row (VertexRules::roulette): 1 for a row without
  // roulette, which then always survives (u < 1) with its throughput unchanged (x / 1 is x).
  Columns3 beta, p, ng, ray_o, ray_d;
  Column t, u_roulette, survival;
  // Outputs. The shadow ray (shadow_ok 1 where one is cast): what it adds if it sees the
  // light.
  Columns3 shadow_c;
  Column shadow_ok;
  // The next ray (alive 1 where the path goes on): the new throughput.
  Columns3 next_beta;
  Column alive;
  // Where the shadow ray and the next ray start, and where the shadow ray ends
  // (shadow_ray_tmax), as the tracer takes them: computed in double, rounded to nearest float
  // (ray_cast<float>).
  FloatColumns3 shadow_o, next_o;
  FloatColumn shadow_tmax;

  std::size_t size() const { return size_; }
  // Rows [0, n), padded to a multiple of 8 lanes. Rows below n keep their values; the columns
  // never shrink.
  void resize(std::size_t n);

 private:
  std::size_t size_ = 0;
};

// A stream filter over a batch's rows, for the write-back of shadow rays and next rays: the
// rows whose keep flag is not 0 (the vertex lanes' shadow_ok or alive), copied in order from
// each source column into its destination (filter_rows returns how many). Columns hold 4-byte
// values (floats, indices) or 8-byte ones (doubles), moved as they are. A destination needs
// room for `rows` values; what lies past the kept ones is overwritten (the lanes store whole
// registers), nothing at or past `rows`.
struct RowFilter {
  static constexpr int kMaxColumns = 10;
  const double* keep = nullptr;
  std::array<const void*, kMaxColumns> from4{}, from8{};
  std::array<void*, kMaxColumns> to4{}, to8{};
  int columns4 = 0, columns8 = 0;

  template <class T>
  void add(const T* from, T* to) {
    static_assert(sizeof(T) == 4 || sizeof(T) == 8, "4- or 8-byte values");
    static_assert(std::is_trivially_copyable_v<T>, "values moved as bytes");
    assert((sizeof(T) == 4 ? columns4 : columns8) < kMaxColumns);
    if constexpr (sizeof(T) == 4)
      from4[columns4] = from, to4[columns4++] = to;
    else
      from8[columns8] = from, to8[columns8++] = to;
  }
};
std::size_t filter_rows(Isa isa, const RowFilter& filter, std::size_t rows);

// The rows' rays into the batches, for the vertex steps and the BSDF: row r's ray is the
// stream's ray rows[r] (r < n), its origin and direction widened to double (exactly) into
// vertices.ray_o and ray_d, its direction turned around, still float, into shade.wo. Both
// batches must have room for n rows (resize).
void gather_vertex_rays(Isa isa, const RayStream& rays, const uint32_t* rows, std::size_t n,
                        VertexBatch& vertices, ShadeBatch& shade);

struct VertexRules {
  bool mis = false;       // weigh the shadow ray by the power heuristic (else 1)
  bool roulette = false;  // Russian roulette at this depth (the lanes: at some rows)
  double survival = 1;    // roulette's survival probability (the lanes: the survival column)
};

// The batch's shadow rays and next rays. Row r's light point is row r of `lights` (its
// cones.wi, cones.dist, le and cones.pdf; a pdf not above 0: none), or none for every row
// without `lights`; its BSDF's answers are row r of `bsdf` (sample: wi, value, pdf; at the
// light point: light_f, light_pdf), widened to double exactly. Both are read as their steps left
// them, padded at least as far as `batch`.
void finish_vertices(Isa isa, const VertexRules& rules, const ShadeBatch& bsdf,
                     const LightQueries* lights, VertexBatch& batch);

// The scalar steps the lanes transcribe, which the double shading takes one vertex at a time.
// The ray origins are offset_ray_origin(p, hit_point_error(ray, t), ng, direction), the shadow
// ray's end shadow_ray_tmax(origin, p, light_wi, light_dist) (core/ray_offset.h).
//
// A shadow ray's contribution if it sees the light, beta·f·Le·(w / light_pdf) with w the power
// heuristic under MIS: false when it has none (no light point, f = 0, or not finite).
bool shadow_contribution(const VertexRules& rules, const glm::dvec3& beta, const glm::dvec3& f,
                         const glm::dvec3& le, double light_pdf, double bsdf_pdf, glm::dvec3& c);
// The throughput after the BSDF's sample, beta·value / pdf, and Russian roulette: false when
// the path ends (no sample, roulette, or a zero or non-finite throughput).
bool next_throughput(const VertexRules& rules, const glm::dvec3& beta, const glm::dvec3& value,
                     double pdf, double u_roulette, glm::dvec3& next);

}  // namespace raylane
