// finish_vertices (render/vertex_lanes.h) in double lanes, instantiated per instruction set by
// src/render/render_lanes_<isa>.cpp. Include from nowhere else. Each step is the scalar code's
// (wavefront/double_vertices.cpp's queue_shadow_ray and continue_path, core/ray_offset.cpp,
// power_heuristic, next_double_up/down) in the same order; the build has -ffp-contract=off, so the
// two agree bit for bit.
#pragma once

#include <cstring>
#include <limits>

#include "raylane/core/float_util.h"
#include "raylane/render/vertex_lanes.h"
#include "raylane/render/vertex_steps.h"
#include "raylane/simd/lane_rows.h"
#include "render/lights/light_lanes_impl.h"

namespace raylane::detail {

template <class A>
using DMask = xsimd::batch_bool<double, A>;

// Finite in every component (|x| ≤ DBL_MAX is false for NaN and ±inf).
template <class A>
DMask<A> all_finite(const DoubleVec3<A>& v) {
  const Doubles<A> big(std::numeric_limits<double>::max());
  return (xsimd::abs(v.x) <= big) & (xsimd::abs(v.y) <= big) & (xsimd::abs(v.z) <= big);
}

template <class A>
DMask<A> all_zero(const DoubleVec3<A>& v) {
  const Doubles<A> zero(0.0);
  return (v.x == zero) & (v.y == zero) & (v.z == zero);
}

// The error bound of a hit point along its geometric normal, dot(|ng|, hit_point_error) as
// offset_ray_origin weighs it, times ng: the offset before its sign. The shadow ray and the
// next ray leave one point, so the vertex computes it once for both.
template <class A>
DoubleVec3<A> offset_along_normal(const DoubleVec3<A>& o, const DoubleVec3<A>& d,
                                  const Doubles<A>& t, const DoubleVec3<A>& ng) {
  using D = Doubles<A>;
  const D bound(32 * kFloatUnitRoundoff);
  auto err = [&](const D& ok, const D& dk) {
    return (xsimd::abs(ok) + xsimd::abs(dk * t)) * bound;
  };
  const D along = xsimd::abs(ng.x) * err(o.x, d.x) + xsimd::abs(ng.y) * err(o.y, d.y) +
                  xsimd::abs(ng.z) * err(o.z, d.z);
  return {ng.x * along, ng.y * along, ng.z * along};
}

// p + off rounded one unit in the last place further from p, as offset_ray_origin's
// next_double_up (off > 0) and next_double_down (off < 0); unchanged where off is 0 or NaN.
// One step instead of both: away from p is up the magnitude where the sum has off's sign, down
// it where not (both nonzero); a zero sum steps to the least denormal of off's sign, an infinite
// one growing stays, and NaN stays, as the scalar functions leave them.
template <class A>
Doubles<A> step_off_point(const Doubles<A>& pk, const Doubles<A>& off) {
  using D = Doubles<A>;
  using I = xsimd::batch<int64_t, A>;
  const D sum = pk + off;
  const auto up = off > D(0.0), down = off < D(0.0);
  // The sum has off's sign (nonzero, not NaN). Not `(sum > 0) ^ down`: xsimd's masks combine by
  // &, | and ! only (simd/lanes.h; the test's infinite points caught it).
  const auto grows = ((sum > D(0.0)) & up) | ((sum < D(0.0)) & down);
  const I bits = xsimd::bitwise_cast<I>(sum);
  const D stepped = xsimd::select(grows, xsimd::bitwise_cast<D>(bits + I(1)),
                                  xsimd::bitwise_cast<D>(bits - I(1)));
  const double least = std::numeric_limits<double>::denorm_min();
  const D from_zero = xsimd::select(up, D(least), D(-least));
  const auto stays =
      xsimd::isnan(sum) | (grows & (xsimd::abs(sum) == D(std::numeric_limits<double>::infinity())));
  const D moved = xsimd::select(sum == D(0.0), from_zero, xsimd::select(stays, sum, stepped));
  return xsimd::select(up | down, moved, sum);
}

// offset_ray_origin (core/ray_offset.cpp) from offset_along_normal's answer: the offset turned
// to the side of ng that `toward` leaves by.
template <class A>
DoubleVec3<A> offset_origin_lanes(const DoubleVec3<A>& p, const DoubleVec3<A>& offset,
                                  const DoubleVec3<A>& ng, const DoubleVec3<A>& toward) {
  using D = Doubles<A>;
  const auto away = ng.x * toward.x + ng.y * toward.y + ng.z * toward.z < D(0.0);
  auto one = [&](const D& pk, const D& ok) {
    return step_off_point<A>(pk, xsimd::select(away, simd::negate(ok), ok));
  };
  return {one(p.x, offset.x), one(p.y, offset.y), one(p.z, offset.z)};
}

template <class A>
Doubles<A> as_flag(const DMask<A>& m) {
  return xsimd::select(m, Doubles<A>(1.0), Doubles<A>(0.0));
}

// Float columns [i, i + W) widened to double lanes.
template <class A>
Doubles<A> load_widened(const std::vector<float>& c, std::size_t i) {
  return simd::load_widened<A>(c.data() + i);
}
template <class A>
DoubleVec3<A> load3_widened(const std::array<std::vector<float>, 3>& c, std::size_t i) {
  return {load_widened<A>(c[0], i), load_widened<A>(c[1], i), load_widened<A>(c[2], i)};
}

// Double lanes rounded to float into float columns [i, i + W).
template <class A>
void store3_narrowed(std::array<std::vector<float>, 3>& c, std::size_t i, const DoubleVec3<A>& v) {
  simd::store_narrowed<A>(c[0].data() + i, v.x);
  simd::store_narrowed<A>(c[1].data() + i, v.y);
  simd::store_narrowed<A>(c[2].data() + i, v.z);
}

// queue_shadow_ray's contribution (render/vertex_steps.h, the scalar steps' own text) and
// origin, for the rows of lanes [i, i + W).
template <class A>
void shadow_lanes(const VertexRules& rules, const ShadeBatch& bsdf, const LightQueries& lights,
                  VertexBatch& b, std::size_t i, const DoubleVec3<A>& beta, const DoubleVec3<A>& p,
                  const DoubleVec3<A>& ng, const DoubleVec3<A>& offset) {
  using D = Doubles<A>;
  const DoubleVec3<A> wi = load3<A>(lights.cones.wi, i), le = load3<A>(lights.le, i),
                      f = load3_widened<A>(bsdf.light_f, i);
  const D pdf = D::load_unaligned(lights.cones.pdf.data() + i);
  const D bsdf_pdf = load_widened<A>(bsdf.light_pdf, i);
  const DoubleVec3<A> c = shadow_ray_contribution(rules.mis, beta, f, le, pdf, bsdf_pdf);
  store3<A>(b.shadow_c, i, c);
  const DoubleVec3<A> from = offset_origin_lanes<A>(p, offset, ng, wi);
  store3_narrowed<A>(b.shadow_o, i, from);
  // shadow_ray_tmax: the light point projected on the ray, in dot's order; inf stays inf.
  const D dist = D::load_unaligned(lights.cones.dist.data() + i);
  const D along = (p.x - from.x) * wi.x + (p.y - from.y) * wi.y + (p.z - from.z) * wi.z;
  simd::store_narrowed<A>(b.shadow_tmax.data() + i,
                          xsimd::select(xsimd::isinf(dist), dist, dist + along));
  // No light point (pdf 0, or NaN): no shadow ray, whatever the other columns hold.
  as_flag<A>((pdf > D(0.0)) & !all_zero<A>(f) & all_finite<A>(c))
      .store_unaligned(b.shadow_ok.data() + i);
}

// continue_path's throughput (render/vertex_steps.h: beta·value / pdf, then roulette) and
// origin.
template <class A>
void continue_lanes(const VertexRules& rules, const ShadeBatch& bsdf, VertexBatch& b, std::size_t i,
                    const DoubleVec3<A>& beta, const DoubleVec3<A>& p, const DoubleVec3<A>& ng,
                    const DoubleVec3<A>& offset) {
  using D = Doubles<A>;
  const DoubleVec3<A> wi = load3_widened<A>(bsdf.wi, i), value = load3_widened<A>(bsdf.value, i);
  const D pdf = load_widened<A>(bsdf.pdf, i);
  DoubleVec3<A> nb = sampled_throughput(beta, value, pdf);
  DMask<A> alive = pdf > D(0.0);
  if (rules.roulette) {  // each row's survival (1 where it has no roulette)
    const D u = D::load_unaligned(b.u_roulette.data() + i);
    const D s = D::load_unaligned(b.survival.data() + i);
    alive = alive & !(u >= s);
    nb = survivor_throughput(nb, s);
  }
  alive = alive & all_finite<A>(nb) & !all_zero<A>(nb);
  store3<A>(b.next_beta, i, nb);
  store3_narrowed<A>(b.next_o, i, offset_origin_lanes<A>(p, offset, ng, wi));
  as_flag<A>(alive).store_unaligned(b.alive.data() + i);
}

template <class A>
void finish_vertices_range(const VertexRules& rules, const ShadeBatch& bsdf,
                           const LightQueries* lights, VertexBatch& b) {
  constexpr std::size_t W = Doubles<A>::size;
  for (std::size_t i = 0; i < b.size(); i += W) {
    const DoubleVec3<A> beta = load3<A>(b.beta, i), p = load3<A>(b.p, i), ng = load3<A>(b.ng, i);
    const DoubleVec3<A> o = load3<A>(b.ray_o, i), d = load3<A>(b.ray_d, i);
    const Doubles<A> t = Doubles<A>::load_unaligned(b.t.data() + i);
    const DoubleVec3<A> offset = offset_along_normal<A>(o, d, t, ng);
    if (lights)
      shadow_lanes<A>(rules, bsdf, *lights, b, i, beta, p, ng, offset);
    else
      Doubles<A>(0.0).store_unaligned(b.shadow_ok.data() + i);
    continue_lanes<A>(rules, bsdf, b, i, beta, p, ng, offset);
  }
}

// gather_vertex_rays: a batch of rows that is one run of the stream (the render's rows are its
// rays in order, most of them going on) loads its columns whole, any other gathers them.
template <class A>
void gather_vertex_rays_range(const RayStream& rays, const uint32_t* rows, std::size_t n,
                              VertexBatch& vertices, ShadeBatch& shade) {
  constexpr std::size_t W = Doubles<A>::size;
  const float* from[6] = {rays.ox.data(), rays.oy.data(), rays.oz.data(),
                          rays.dx.data(), rays.dy.data(), rays.dz.data()};
  double* to[6] = {vertices.ray_o[0].data(), vertices.ray_o[1].data(), vertices.ray_o[2].data(),
                   vertices.ray_d[0].data(), vertices.ray_d[1].data(), vertices.ray_d[2].data()};
  float* wo[3] = {shade.wo[0].data(), shade.wo[1].data(), shade.wo[2].data()};
  std::size_t i = 0;
  for (; i + W <= n; i += W) {
    const uint32_t* at = rows + i;
    const bool run = simd::one_run<int(W)>(at);
    for (int c = 0; c < 6; ++c) {
      const Doubles<A> x =
          run ? simd::load_widened<A>(from[c] + at[0]) : simd::load_rows<A>(from[c], at);
      x.store_unaligned(to[c] + i);
      if (c >= 3)
        simd::store_narrowed<A>(wo[c - 3] + i, simd::negate(x));  // -float(x) (quiet NaNs)
    }
  }
  for (; i < n; ++i)
    for (int c = 0; c < 6; ++c) {
      const float x = from[c][rows[i]];
      to[c][i] = x;
      if (c >= 3) wo[c - 3][i] = -x;
    }
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
    uint32_t keep = 0;  // "not 0" as the scalar rows test it: a NaN flag keeps its row
    for (std::size_t j = 0; j < W; j += WD)
      keep |= simd::bits<A>(!(Doubles<A>::load_unaligned(f.keep + i + j) == Doubles<A>(0.0))) << j;
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
