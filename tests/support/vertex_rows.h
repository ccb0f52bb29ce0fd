// Random vertices for the vertex lanes' tests (render/vertex_lanes.h): the rows as the columns
// hold them, their batches filled from them, and the comparisons of rays bit for bit.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "raylane/core/ray_offset.h"
#include "raylane/core/warps.h"
#include "raylane/render/lights/lights.h"
#include "raylane/render/materials/shade_lanes.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/vertex_lanes.h"
#include "support/same_bits.h"

namespace raylane::testing {

using Vec = glm::vec3;

// One vertex as the columns hold it: float, but for the light point's double columns (the
// kernel rounds them to float as it reads them).
struct Vertex {
  Vec beta{}, p{}, ng{}, o{}, d{};
  float t;
  Vec light_wi{}, f{};
  glm::dvec3 le{};
  double light_dist, light_pdf;
  float bsdf_pdf;
  Vec wi{}, value{};
  float pdf, u;
};

inline Vec random_unit(Rng& rng) {
  return Vec(sample_uniform_sphere(rng.uniform(), rng.uniform()));
}

// Scales over many decades, so that offsets and throughputs meet their rounding edges.
inline double spread(Rng& rng, double lo_exp, double hi_exp) {
  return std::pow(10.0, lo_exp + (hi_exp - lo_exp) * rng.uniform());
}

inline Vec bound_of(const Vertex& v) {
  return float_hit_point_bound<float>(v.o, v.d, v.t, v.p);
}

// The x component of the offset (core/ray_offset.h's offset_origin), before its step.
inline float offset_x(const Vertex& v) {
  const Vec e = bound_of(v);
  return v.ng.x * (std::abs(v.ng.x) * e.x + std::abs(v.ng.y) * e.y + std::abs(v.ng.z) * e.z);
}

inline Vertex random_vertex(Rng& rng, int i) {
  Vertex v;
  v.beta = Vec(float(rng.uniform()), float(rng.uniform()), float(rng.uniform())) *
           float(spread(rng, -3, 3));
  v.d = random_unit(rng);
  v.o = random_unit(rng) * float(spread(rng, -2, 4));
  v.t = float(spread(rng, -6, 3));
  v.p = i % 17 == 0 ? Vec(0) : v.o + v.d * v.t;
  v.ng = i % 5 == 0 ? Vec(0, i % 2 ? 1.0f : -1.0f, 0) : random_unit(rng);
  v.light_wi = random_unit(rng);
  v.light_dist = i % 37 == 0 ? std::numeric_limits<double>::infinity() : spread(rng, -4, 4);
  v.le = glm::dvec3(1, 2, 3) * spread(rng, -1, 2);
  v.f = i % 13 == 0 ? Vec(0) : Vec(float(rng.uniform()), float(rng.uniform()), 0.5f);
  v.light_pdf = i % 11 == 0 ? 0.0 : spread(rng, -3, 3);
  if (i % 97 == 0) v.light_pdf = 1e-320;  // below float's range: no light point at float
  if (i % 101 == 0) v.light_pdf = 1e30;   // a square beyond float's range: MIS must not overflow
  v.bsdf_pdf = i % 7 == 0 ? 0.0f : float(spread(rng, -3, 3));
  v.wi = random_unit(rng);
  v.value =
      i % 19 == 0 ? Vec(0) : Vec(float(rng.uniform()), float(rng.uniform()), float(rng.uniform()));
  v.pdf = i % 23 == 0 ? 0.0f : float(spread(rng, -3, 3));
  if (i % 89 == 0) {  // a throughput that overflows
    v.pdf = std::numeric_limits<float>::denorm_min();
    v.beta = v.beta * 1e30f;
  }
  v.u = i % 29 == 0 ? 0.8f : float(rng.uniform());  // roulette's threshold itself ends the path
  if (i % 31 == 0) {
    // The offset lands exactly on 0: the origin must still step off it (to the least denormal).
    // The normal leans 2^-8 towards x, so that p.x barely moves its own bound: p.x = −offset.x
    // reaches a float fixed point in a step or two.
    v.ng = {0x1p-8f, 1, 0};
    v.light_wi = v.wi = normalize(Vec(1, 0.5f, -0.5f));
    v.p.x = 0;
    for (int k = 0; k < 10 && v.p.x + offset_x(v) != 0; ++k)
      v.p.x = -offset_x(v);
  }
  // Points off the end of the floats: infinite, or not a number (one or the other: where two
  // NaNs meet in a sum, which one's sign survives depends on the operands' order, which the
  // compiler may swap).
  const float inf = std::numeric_limits<float>::infinity();
  if (i % 43 == 0)
    v.p[i % 3] = i % 2 ? inf : -inf;
  else if (i % 47 == 0)
    v.p[i % 3] = std::numeric_limits<float>::quiet_NaN();  // (same_origin, below)
  else if (i % 59 == 0) {
    // A point at −0 on a face along an axis, from an origin at 0: the offset's zero components
    // (±0, turned with the side) decide the signs of the origin's zeros.
    v.o = Vec(0), v.t = 0;
    v.p = {-0.0f, v.p.y, -0.0f};
    v.ng = {0, i % 2 ? 1.0f : -1.0f, 0};
  } else if (i % 61 == 0) {
    v.t = std::numeric_limits<float>::quiet_NaN();  // no bound on the point's error: NaN
  } else if (i % 67 == 0) {
    // The ends of the range and the least denormals: the step off them (to ±inf, across 0).
    const float big = std::numeric_limits<float>::max(), tiny = 0x1p-149f;
    v.o = Vec(0), v.t = 0;
    v.p = {i % 2 ? big : -big, i % 3 ? tiny : -tiny, 0};
  }
  return v;
}

// The vertices into the batches the vertex lanes read: their own, the BSDF's answers and the
// light points.
struct Batches {
  VertexBatch vertex;
  ShadeBatch bsdf;
  LightQueries lights;
};

// Row i's rules under `rules`: with `mixed`, every third row has no roulette (a wavefront that
// refills holds rows of several depths).
inline VertexRules rules_of_row(const VertexRules& rules, bool mixed, std::size_t i) {
  VertexRules r = rules;
  if (mixed && i % 3 == 0) r.roulette = false;
  return r;
}

inline void fill(Batches& b, const std::vector<Vertex>& vs, const VertexRules& rules, bool mixed) {
  b.vertex.resize(vs.size()), b.bsdf.resize(vs.size()), b.lights.resize(vs.size());
  VertexBatch& vb = b.vertex;
  ShadeBatch& sb = b.bsdf;
  LightQueries& q = b.lights;
  for (std::size_t i = 0; i < vs.size(); ++i) {
    const Vertex& v = vs[i];
    for (std::size_t k = 0; k < 3; ++k) {
      vb.beta[k][i] = v.beta[k], vb.p[k][i] = v.p[k], vb.ng[k][i] = v.ng[k];
      vb.p_error[k][i] = bound_of(v)[k], sb.wo[k][i] = -v.d[k];
      sb.light_wi[k][i] = v.light_wi[k], q.le[k][i] = v.le[k];
      sb.light_f[k][i] = v.f[k], sb.wi[k][i] = v.wi[k], sb.value[k][i] = v.value[k];
    }
    const VertexRules row_rules = rules_of_row(rules, mixed, i);
    vb.u_roulette[i] = v.u;
    vb.survival[i] = row_rules.roulette ? float(row_rules.survival) : 1.0f;
    q.cones.dist[i] = v.light_dist, q.cones.pdf[i] = v.light_pdf;
    sb.light_pdf[i] = v.bsdf_pdf, sb.pdf[i] = v.pdf;
  }
}

template <class T>
glm::vec<3, T> row(const std::array<std::vector<T>, 3>& c, std::size_t i) {
  return {c[0][i], c[1][i], c[2][i]};
}

// An origin's components (and a shadow ray's end) bit for bit, or both NaN: a NaN point makes its
// bound NaN too, and where the two NaNs meet in p + offset which one's sign survives depends on the
// operands' order, which the compiler may swap. Either way the ray is invalid (the tracer skips
// it).
inline bool same_or_nan(float a, float b) {
  return same_bits(a, b) || (std::isnan(a) && std::isnan(b));
}
inline bool same_origin(const Vec& a, const Vec& b) {
  return same_or_nan(a.x, b.x) && same_or_nan(a.y, b.y) && same_or_nan(a.z, b.z);
}

// n rows of random vertices in a batch, and its padding rows past n holding an earlier
// wavefront's vertices, as the render's do (the columns never shrink): rows to be queued
// nowhere, though they would go on.
inline Batches random_rows(Rng& rng, std::size_t n, const VertexRules& rules) {
  const std::size_t padded = (n + 15) / 16 * 16;
  std::vector<Vertex> vs;
  for (std::size_t i = 0; i < padded; ++i)
    vs.push_back(random_vertex(rng, int(i)));
  Batches b;
  fill(b, vs, rules, true);
  b.vertex.resize(n), b.bsdf.resize(n), b.lights.resize(n);
  return b;
}

}  // namespace raylane::testing
