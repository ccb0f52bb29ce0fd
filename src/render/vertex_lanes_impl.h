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

// The shadow ray of rows [i, i + W): its contribution (render/vertex_steps.h), origin, direction
// (the light point's, as the BSDF was evaluated toward it) and end, and whether there is one.
template <class A>
struct ShadowLanes {
  FloatVec3<A> c, from, wi;
  F<A> tmax;
  M<A> ok;
};

// The rows' light radiance: the one light's as broadcast lanes (LightQueries::one_light), else
// the column's.
template <class A>
[[gnu::always_inline]] inline FloatVec3<A> light_radiance(const LightQueries& lights,
                                                          std::size_t i) {
  if (const auto& one = lights.one_light)
    return {F<A>(one->le[0]), F<A>(one->le[1]), F<A>(one->le[2])};
  return load3<A>(lights.le, i);
}

// The rows' lights as their bits, likewise.
template <class A>
[[gnu::always_inline]] inline simd::Ints<A> light_bits(const LightQueries& lights, std::size_t i) {
  if (const auto& one = lights.one_light) return simd::Ints<A>(int32_t(one->light.bits()));
  return simd::Ints<A>::load_unaligned(reinterpret_cast<const int32_t*>(lights.light.data() + i));
}

// Inlined always, as next_lanes: called out of line (GCC's choice once the kernel grew), its
// eleven registers of answers went back through memory.
template <class A>
[[gnu::always_inline]] inline ShadowLanes<A> shadow_lanes(const VertexRules& rules,
                                                          const BsdfAnswers<A>& a,
                                                          const ShadeBatch& bsdf,
                                                          const LightQueries& lights,
                                                          const VertexLanes<A>& v, std::size_t i) {
  ShadowLanes<A> s;
  s.wi = load3<A>(bsdf.light_wi, i);
  const FloatVec3<A> le = light_radiance<A>(lights, i);
  const FloatVec3<A> f{a.light_f[0], a.light_f[1], a.light_f[2]};
  const F<A> pdf = simd::load<A>(lights.cones.pdf.data() + i);
  s.c = shadow_ray_contribution(rules.mis, v.beta, f, le, pdf, a.light_pdf);
  s.from = offset_origin_by<F<A>>(v.p, v.along, v.ng, s.wi);
  const F<A> dist = simd::load<A>(lights.cones.dist.data() + i);
  s.tmax = shadow_tmax<F<A>>(s.from, v.p, s.wi, dist);
  // No light point (pdf 0, or NaN): no shadow ray, whatever the other lanes hold.
  s.ok = (pdf > F<A>(0.0f)) & !all_zero<A>(f) & all_finite<A>(s.c);
  return s;
}

// The throughput after the BSDF's sample (beta·value / pdf, then roulette), the next origin,
// and whether the path goes on.
template <class A>
struct NextLanes {
  FloatVec3<A> beta, o;
  M<A> alive;
};

template <class A>
[[gnu::always_inline]] inline NextLanes<A> next_lanes(const VertexRules& rules,
                                                      const BsdfAnswers<A>& a,
                                                      const VertexLanes<A>& v, const VertexBatch& b,
                                                      std::size_t i) {
  const FloatVec3<A> value{a.value[0], a.value[1], a.value[2]};
  NextLanes<A> n;
  n.beta = sampled_throughput(v.beta, value, a.pdf);
  M<A> alive = a.pdf > F<A>(0.0f);
  if (rules.roulette) {  // each row's survival (1 where it has no roulette)
    const F<A> u = simd::load<A>(b.u_roulette.data() + i);
    const F<A> s = simd::load<A>(b.survival.data() + i);
    alive = alive & !(u >= s);
    n.beta = survivor_throughput(n.beta, s);
  }
  n.alive = alive & all_finite<A>(n.beta) & !all_zero<A>(n.beta);
  n.o = offset_origin_by<F<A>>(v.p, v.along, v.ng, a.wi);
  return n;
}

// finish_vertices' steps for rows [i, i + W), into the batch's columns.
template <class A>
void vertex_steps(const VertexRules& rules, const BsdfAnswers<A>& a, const ShadeBatch& bsdf,
                  const LightQueries* lights, VertexBatch& b, std::size_t i) {
  const VertexLanes<A> v(b, i);
  if (lights) {
    const ShadowLanes<A> s = shadow_lanes<A>(rules, a, bsdf, *lights, v, i);
    for (int k = 0; k < 3; ++k)
      simd::store_widened<A>(b.shadow_c[k].data() + i, k == 0 ? s.c.x : k == 1 ? s.c.y : s.c.z);
    store3<A>(b.shadow_o, i, s.from);
    simd::store<A>(b.shadow_tmax.data() + i, s.tmax);
    simd::store<A>(b.shadow_ok.data() + i, as_flag<A>(s.ok));
  } else {
    simd::store<A>(b.shadow_ok.data() + i, F<A>(0.0f));
  }
  const NextLanes<A> n = next_lanes<A>(rules, a, v, b, i);
  store3<A>(b.next_beta, i, n.beta);
  store3<A>(b.next_o, i, n.o);
  simd::store<A>(b.alive.data() + i, as_flag<A>(n.alive));
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

// The kept lanes of three registers into three destinations at `at`.
template <class A>
void pack3(const simd::LanePacker<A>& pack, const std::array<float*, 3>& to, std::size_t at,
           const FloatVec3<A>& v) {
  pack.store(to[0] + at, v.x), pack.store(to[1] + at, v.y), pack.store(to[2] + at, v.z);
}

// scatter_vertices: the BSDF and the steps after it, a batch of rows at a time, the BSDF's
// answers and the steps' results in registers, each ray packed into its queue as it is made.
// The destinations are copied first: stores through them may alias anything not provably local,
// and their pointers would be reloaded after each one.
template <class A>
void scatter_range(const LaneMaterials& materials, const VertexRules& rules, ShadeBatch& bsdf,
                   const LightQueries* lights, VertexBatch& b, VertexQueues& queues) {
  constexpr std::size_t W = simd::kWidth<A>;
  const VertexQueues q = queues;
  const std::size_t n = b.size();
  std::size_t next = 0, shadows = 0;
  for (std::size_t i = 0; i < n; i += W) {
    const BsdfAnswers<A> a = bsdf_answers<A>(materials, bsdf, i);
    // The batch's own rows: the last batch's padding lanes are queued nowhere.
    const uint32_t rows = n - i >= W ? (1u << W) - 1 : (1u << (n - i)) - 1;
    const simd::Ints<A> path =
        simd::Ints<A>::load_unaligned(reinterpret_cast<const int32_t*>(q.path + i));
    const VertexLanes<A> v(b, i);
    if (lights) {
      const ShadowLanes<A> s = shadow_lanes<A>(rules, a, bsdf, *lights, v, i);
      const simd::LanePacker<A> pack(simd::bits<A>(s.ok) & rows);
      pack3<A>(pack, q.shadow_o, shadows, s.from);
      pack3<A>(pack, q.shadow_d, shadows, s.wi);
      pack.store(q.shadow_tmax + shadows, s.tmax);
      pack.store(q.shadow_light + shadows, light_bits<A>(*lights, i));
      pack.store(q.shadow_path + shadows, path);
      pack.store_widened(q.shadow_c[0] + shadows, s.c.x);
      pack.store_widened(q.shadow_c[1] + shadows, s.c.y);
      pack.store_widened(q.shadow_c[2] + shadows, s.c.z);
      shadows += std::size_t(pack.count());
    }
    const NextLanes<A> nx = next_lanes<A>(rules, a, v, b, i);
    const simd::LanePacker<A> pack(simd::bits<A>(nx.alive) & rows);
    pack3<A>(pack, q.next_o, next, nx.o);
    pack3<A>(pack, q.next_d, next, a.wi);
    pack.store(q.next_path + next, path);
    pack.store_widened(q.next_beta[0] + next, nx.beta.x);
    pack.store_widened(q.next_beta[1] + next, nx.beta.y);
    pack.store_widened(q.next_beta[2] + next, nx.beta.z);
    pack3<A>(pack, q.next_prev_p, next, v.p);
    pack.store_widened(q.next_prev_pdf + next, a.pdf);
    pack.store(q.next_depth + next,
               simd::Ints<A>::load_unaligned(reinterpret_cast<const int32_t*>(q.depth + i)) +
                   simd::Ints<A>(1));
    next += std::size_t(pack.count());
  }
  queues.next_count = next, queues.shadow_count = shadows;
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

}  // namespace raylane::detail
