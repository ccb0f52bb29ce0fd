// finish_vertices and scatter_vertices (render/vertex_lanes.h) in float lanes, instantiated per
// instruction set by src/render/render_lanes_<isa>.cpp. Include from nowhere else. Each step is
// written once over the number type (render/vertex_steps.h, core/ray_offset.h); the build has
// -ffp-contract=off, so the lanes and the steps' scalar float instance agree bit for bit.
#pragma once

#include <cstring>
#include <limits>

#include "raylane/core/ray_offset.h"
#include "raylane/render/vertex_lanes.h"
#include "raylane/render/vertex_steps.h"
#include "raylane/simd/lane_convert.h"
#include "raylane/simd/lane_lookup.h"
#include "raylane/simd/lane_numbers.h"
#include "raylane/simd/lane_rows.h"
#include "render/lights/light_lanes_impl.h"
#include "render/materials/shade_lanes_impl.h"

namespace raylane::detail {

// Finite in every component (|x| ≤ FLT_MAX is false for NaN and ±inf).
template <class A>
M<A> all_finite(const FloatVec3<A>& v) {
  return finite<A>(v.x) & finite<A>(v.y) & finite<A>(v.z);
}

template <class A>
M<A> all_zero(const FloatVec3<A>& v) {
  const F<A> zero(0.0f);
  return (v.x == zero) & (v.y == zero) & (v.z == zero);
}

template <class A>
F<A> as_flag(const M<A>& m) {
  return simd::select(m, F<A>(1.0f), F<A>(0.0f));
}

// The vertex of rows [i, i + W): throughput, point, normal, and the bound on the point's error
// projected on the normal, the offset both its rays leave by.
template <class A>
struct VertexLanes {
  FloatVec3<A> beta, p, ng;
  F<A> along;

  VertexLanes(const VertexBatch& b, std::size_t i)
      : beta(load3<A>(b.beta, i)),
        p(load3<A>(b.p, i)),
        ng(load3<A>(b.ng, i)),
        along(offset_along_normal<F<A>>(load3<A>(b.p_error, i), ng)) {}
};

// The shadow ray's contribution (render/vertex_steps.h), origin and end, for rows [i, i + W).
template <class A>
void shadow_lanes(const VertexRules& rules, const BsdfAnswers<A>& a, const ShadeBatch& bsdf,
                  const LightQueries& lights, const VertexLanes<A>& v, VertexBatch& b,
                  std::size_t i) {
  const FloatVec3<A> wi = load3<A>(bsdf.light_wi, i), le = load3<A>(lights.le, i);
  const FloatVec3<A> f{a.light_f[0], a.light_f[1], a.light_f[2]};
  const F<A> pdf = simd::load<A>(lights.cones.pdf.data() + i);
  const FloatVec3<A> c = shadow_ray_contribution(rules.mis, v.beta, f, le, pdf, a.light_pdf);
  for (int k = 0; k < 3; ++k)
    simd::store_widened<A>(b.shadow_c[k].data() + i, k == 0 ? c.x : k == 1 ? c.y : c.z);
  const FloatVec3<A> from = offset_origin_by<F<A>>(v.p, v.along, v.ng, wi);
  store3<A>(b.shadow_o, i, from);
  const F<A> dist = simd::load<A>(lights.cones.dist.data() + i);
  simd::store<A>(b.shadow_tmax.data() + i, shadow_tmax<F<A>>(from, v.p, wi, dist));
  // No light point (pdf 0, or NaN): no shadow ray, whatever the other columns hold.
  simd::store<A>(b.shadow_ok.data() + i,
                 as_flag<A>((pdf > F<A>(0.0f)) & !all_zero<A>(f) & all_finite<A>(c)));
}

// The throughput after the BSDF's sample (beta·value / pdf, then roulette) and the next origin.
template <class A>
void continue_lanes(const VertexRules& rules, const BsdfAnswers<A>& a, const VertexLanes<A>& v,
                    VertexBatch& b, std::size_t i) {
  const FloatVec3<A> value{a.value[0], a.value[1], a.value[2]};
  FloatVec3<A> nb = sampled_throughput(v.beta, value, a.pdf);
  M<A> alive = a.pdf > F<A>(0.0f);
  if (rules.roulette) {  // each row's survival (1 where it has no roulette)
    const F<A> u = simd::load<A>(b.u_roulette.data() + i);
    const F<A> s = simd::load<A>(b.survival.data() + i);
    alive = alive & !(u >= s);
    nb = survivor_throughput(nb, s);
  }
  alive = alive & all_finite<A>(nb) & !all_zero<A>(nb);
  store3<A>(b.next_beta, i, nb);
  store3<A>(b.next_o, i, offset_origin_by<F<A>>(v.p, v.along, v.ng, a.wi));
  simd::store<A>(b.alive.data() + i, as_flag<A>(alive));
}

// The steps after the BSDF for rows [i, i + W), from its answers.
template <class A>
void vertex_steps(const VertexRules& rules, const BsdfAnswers<A>& a, const ShadeBatch& bsdf,
                  const LightQueries* lights, VertexBatch& b, std::size_t i) {
  const VertexLanes<A> v(b, i);
  if (lights)
    shadow_lanes<A>(rules, a, bsdf, *lights, v, b, i);
  else
    simd::store<A>(b.shadow_ok.data() + i, F<A>(0.0f));
  continue_lanes<A>(rules, a, v, b, i);
}

// finish_vertices: the BSDF's answers read from its columns.
template <class A>
void finish_vertices_range(const VertexRules& rules, const ShadeBatch& bsdf,
                           const LightQueries* lights, VertexBatch& b) {
  constexpr std::size_t W = simd::kWidth<A>;
  for (std::size_t i = 0; i < b.size(); i += W) {
    BsdfAnswers<A> a;
    a.wi = load3<A>(bsdf.wi, i);
    for (int k = 0; k < 3; ++k) {
      a.value[k] = simd::load<A>(bsdf.value[k].data() + i);
      a.light_f[k] = simd::load<A>(bsdf.light_f[k].data() + i);
    }
    a.pdf = simd::load<A>(bsdf.pdf.data() + i);
    a.light_pdf = simd::load<A>(bsdf.light_pdf.data() + i);
    vertex_steps<A>(rules, a, bsdf, lights, b, i);
  }
}

// scatter_vertices: the BSDF and the steps after it, a batch of rows at a time, the BSDF's
// answers in registers; only the sampled direction and density are stored (the write-back
// reads them).
template <class A>
void scatter_range(const LaneMaterials& materials, const VertexRules& rules, ShadeBatch& bsdf,
                   const LightQueries* lights, VertexBatch& b) {
  constexpr std::size_t W = simd::kWidth<A>;
  for (std::size_t i = 0; i < b.size(); i += W) {
    const BsdfAnswers<A> a = bsdf_answers<A>(materials, bsdf, i);
    store3<A>(bsdf.wi, i, a.wi);
    simd::store<A>(bsdf.pdf.data() + i, a.pdf);
    vertex_steps<A>(rules, a, bsdf, lights, b, i);
  }
}

// gather_wo: a batch of rows reads the stream's columns through a RowReader (the render's rows
// are its rays in order, most of them going on: mostly one run, else close together).
template <class A>
void gather_wo_range(const RayStream& rays, const uint32_t* rows, std::size_t n,
                     ShadeBatch& shade) {
  constexpr std::size_t W = simd::kWidth<A>;
  const float* from[3] = {rays.dx.data(), rays.dy.data(), rays.dz.data()};
  float* to[3] = {shade.wo[0].data(), shade.wo[1].data(), shade.wo[2].data()};
  std::size_t i = 0;
  for (; i + W <= n; i += W) {
    const simd::RowReader<A> read(rows + i);
    for (int c = 0; c < 3; ++c)
      simd::store<A>(to[c] + i, simd::negate(read.read(from[c])));
  }
  for (; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      to[c][i] = -from[c][rows[i]];
}

// filter_rows: whole lane batches through the compressing stores, the last rows one by one.
// The filter is copied first: the stores go through char pointers, which may alias anything the
// compiler cannot see is local, so it reloaded every column pointer and count after each store
// (3 % of a render, perf).
template <class A>
std::size_t filter_rows_range(const RowFilter& filter, std::size_t n) {
  constexpr std::size_t W = simd::kWidth<A>, WD = simd::kDoubleWidth<A>;
  const RowFilter f = filter;
  auto at = [](const void* p, std::size_t bytes) { return static_cast<const char*>(p) + bytes; };
  auto to = [](void* p, std::size_t bytes) { return static_cast<char*>(p) + bytes; };
  std::size_t m = 0, i = 0;
  for (; i + W <= n; i += W) {
    // "not 0" as the scalar rows test it: a NaN flag keeps its row.
    const uint32_t keep = simd::bits<A>(!(simd::load<A>(f.keep + i) == F<A>(0.0f)));
    for (int c = 0; c < f.columns4; ++c)
      simd::store_compressed32<A>(to(f.to4[c], 4 * m), at(f.from4[c], 4 * i), keep);
    std::size_t kept = m;
    for (std::size_t j = 0; j < W; j += WD) {
      const uint32_t part = (keep >> j) & ((1u << WD) - 1);
      for (int c = 0; c < f.columns8; ++c)
        simd::store_compressed64<A>(to(f.to8[c], 8 * kept), at(f.from8[c], 8 * (i + j)), part);
      kept += std::size_t(simd::popcount<A>(part));
    }
    m = kept;
  }
  for (; i < n; ++i) {
    if (f.keep[i] == 0) continue;
    for (int c = 0; c < f.columns4; ++c)
      std::memcpy(to(f.to4[c], 4 * m), at(f.from4[c], 4 * i), 4);
    for (int c = 0; c < f.columns8; ++c)
      std::memcpy(to(f.to8[c], 8 * m), at(f.from8[c], 8 * i), 8);
    ++m;
  }
  return m;
}

}  // namespace raylane::detail
