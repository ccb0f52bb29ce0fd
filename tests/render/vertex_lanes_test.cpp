// What follows the BSDF in double lanes (render/vertex_lanes.h) against the scalar steps the
// double shading takes (shadow_contribution, next_throughput, offset_ray_origin with
// hit_point_error), bit for bit at every instruction set this CPU has, on random vertices and
// on the edges: no light point, f = 0, no sample, roulette's threshold, overflowing
// throughputs, normals along an axis (offsets of 0 in two components), points at 0 and
// offsets that land on 0.
#include "raylane/render/vertex_lanes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "raylane/core/ray_offset.h"
#include "raylane/core/strings.h"
#include "raylane/core/warps.h"
#include "raylane/render/rng.h"
#include "support/same_bits.h"

namespace raylane {
namespace {

// The lanes must give the scalar results bit for bit (support/same_bits.h).
using testing::same_bits;

struct Vertex {
  Vec3d beta, p, ng, o, d;
  double t;
  Vec3d light_wi, le, f;
  double light_dist, light_pdf, bsdf_pdf;
  Vec3d wi, value;
  double pdf, u;
};

Vec3d random_unit(Rng& rng) {
  return sample_uniform_sphere(rng.uniform(), rng.uniform());
}

// Scales over many decades, so that offsets and throughputs meet their rounding edges.
double spread(Rng& rng, double lo_exp, double hi_exp) {
  return std::pow(10.0, lo_exp + (hi_exp - lo_exp) * rng.uniform());
}

Vertex random_vertex(Rng& rng, int i) {
  Vertex v;
  v.beta = Vec3d(rng.uniform(), rng.uniform(), rng.uniform()) * spread(rng, -3, 3);
  v.d = random_unit(rng);
  v.o = random_unit(rng) * spread(rng, -2, 4);
  v.t = spread(rng, -6, 3);
  v.p = i % 17 == 0 ? Vec3d(0, 0, 0) : v.o + v.d * v.t;
  v.ng = i % 5 == 0 ? Vec3d(0, i % 2 ? 1.0 : -1.0, 0) : random_unit(rng);
  v.light_wi = random_unit(rng);
  v.light_dist = i % 37 == 0 ? std::numeric_limits<double>::infinity() : spread(rng, -4, 4);
  v.le = Vec3d(1, 2, 3) * spread(rng, -1, 2);
  v.f = i % 13 == 0 ? Vec3d(0, 0, 0) : Vec3d(rng.uniform(), rng.uniform(), 0.5);
  v.light_pdf = i % 11 == 0 ? 0.0 : spread(rng, -3, 3);
  if (i % 97 == 0) v.light_pdf = 1e-320;  // a contribution that overflows
  v.bsdf_pdf = i % 7 == 0 ? 0.0 : spread(rng, -3, 3);
  v.wi = random_unit(rng);
  v.value = i % 19 == 0 ? Vec3d(0, 0, 0) : Vec3d(rng.uniform(), rng.uniform(), rng.uniform());
  v.pdf = i % 23 == 0 ? 0.0 : spread(rng, -3, 3);
  if (i % 89 == 0) v.pdf = 1e-320;          // a throughput that overflows
  v.u = i % 29 == 0 ? 0.8 : rng.uniform();  // roulette's threshold itself ends the path
  if (i % 31 == 0) {
    // The offset lands exactly on 0: the origin must still step off it (to the least denormal).
    v.ng = {1, 0, 0};
    v.light_wi = v.wi = normalize(Vec3d(1, 0.5, -0.5));
    v.p.x = -hit_point_error(Rayd{v.o, v.d}, v.t).x;
  }
  return v;
}

void fill(VertexBatch& b, const std::vector<Vertex>& vs) {
  b.resize(vs.size());
  for (std::size_t i = 0; i < vs.size(); ++i) {
    const Vertex& v = vs[i];
    for (int k = 0; k < 3; ++k) {
      b.beta[k][i] = v.beta[k], b.p[k][i] = v.p[k], b.ng[k][i] = v.ng[k];
      b.ray_o[k][i] = v.o[k], b.ray_d[k][i] = v.d[k];
      b.light_wi[k][i] = v.light_wi[k], b.light_le[k][i] = v.le[k], b.light_f[k][i] = v.f[k];
      b.wi[k][i] = v.wi[k], b.value[k][i] = v.value[k];
    }
    b.t[i] = v.t, b.light_dist[i] = v.light_dist, b.light_pdf[i] = v.light_pdf,
    b.light_bsdf_pdf[i] = v.bsdf_pdf;
    b.pdf[i] = v.pdf, b.u_roulette[i] = v.u;
  }
}

Vec3d row(const VertexBatch::Columns3& c, std::size_t i) {
  return {c[0][i], c[1][i], c[2][i]};
}

// Counts of what the rows exercised, so the test can require every branch.
struct Seen {
  int shadows = 0, no_shadow = 0, alive = 0, ended = 0, environment = 0;
};

void expect_rows_are_scalar(const VertexRules& rules, const std::vector<Vertex>& vs,
                            const VertexBatch& b, Seen& seen) {
  int failures = 0;
  for (std::size_t i = 0; i < vs.size() && failures < 10; ++i) {
    const Vertex& v = vs[i];
    Rayd ray{v.o, v.d};
    Vec3d err = hit_point_error(ray, v.t);
    Vec3d c;
    bool shadow = shadow_contribution(rules, v.beta, v.f, v.le, v.light_pdf, v.bsdf_pdf, c);
    bool ok = (b.shadow_ok[i] != 0) == shadow;
    if (shadow) {
      const Vec3d o = offset_ray_origin(v.p, err, v.ng, v.light_wi);
      ok = ok && same_bits(row(b.shadow_c, i), c) && same_bits(row(b.shadow_o, i), o) &&
           same_bits(b.shadow_tmax[i], shadow_ray_tmax(o, v.p, v.light_wi, v.light_dist));
      seen.environment += std::isinf(v.light_dist);
    }
    Vec3d next;
    bool alive = next_throughput(rules, v.beta, v.value, v.pdf, v.u, next);
    ok = ok && (b.alive[i] != 0) == alive;
    if (alive)
      ok = ok && same_bits(row(b.next_beta, i), next) &&
           same_bits(row(b.next_o, i), offset_ray_origin(v.p, err, v.ng, v.wi));
    failures += !ok;
    EXPECT_TRUE(ok) << "row " << i << ": shadow " << shadow << " alive " << alive;
    ++(shadow ? seen.shadows : seen.no_shadow);
    ++(alive ? seen.alive : seen.ended);
  }
}

TEST(VertexLanes, ShadowRaysAndNextRaysAreTheScalarOnes) {
  Rng rng(11);
  std::vector<Vertex> vs;
  for (int i = 0; i < 20000; ++i)
    vs.push_back(random_vertex(rng, i));
  for (Isa isa : supported_isas())
    for (bool mis : {false, true})
      for (bool roulette : {false, true}) {
        SCOPED_TRACE(cat("isa ", isa_name(isa), " mis ", mis, " roulette ", roulette));
        const VertexRules rules{mis, roulette, 0.8};
        VertexBatch b;
        fill(b, vs);
        finish_vertices(isa, rules, b);
        Seen seen;
        expect_rows_are_scalar(rules, vs, b, seen);
        EXPECT_GT(seen.shadows, 10000);
        EXPECT_GT(seen.environment, 200);
        EXPECT_GT(seen.no_shadow, 2000);
        EXPECT_GT(seen.alive, 10000);
        EXPECT_GT(seen.ended, roulette ? 4000 : 1000);
      }
}

// The scalar steps themselves, on values whose answers are known.
TEST(VertexLanes, ScalarStepsOnKnownValues) {
  VertexRules rules{true, true, 0.8};
  Vec3d c;
  // Equal densities: the power heuristic weighs 1/2; beta·f·Le·(1/2)/2.
  ASSERT_TRUE(shadow_contribution(rules, {1, 2, 4}, {0.5, 0.5, 0.5}, {2, 2, 2}, 2, 2, c));
  EXPECT_EQ(c, Vec3d(0.25, 0.5, 1));
  EXPECT_FALSE(shadow_contribution(rules, {1, 1, 1}, {0, 0, 0}, {1, 1, 1}, 1, 1, c));
  EXPECT_FALSE(shadow_contribution(rules, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}, 0, 1, c));
  Vec3d next;
  ASSERT_TRUE(next_throughput(rules, {1, 1, 1}, {0.4, 0.8, 1.6}, 0.5, 0.5, next));
  EXPECT_EQ(next, Vec3d(0.4 / 0.5 / 0.8, 0.8 / 0.5 / 0.8, 1.6 / 0.5 / 0.8));
  EXPECT_FALSE(next_throughput(rules, {1, 1, 1}, {1, 1, 1}, 1, 0.8, next));  // roulette ends it
  rules.roulette = false;
  ASSERT_TRUE(next_throughput(rules, {1, 1, 1}, {1, 1, 1}, 1, 0.9, next));
  EXPECT_EQ(next, Vec3d(1, 1, 1));
  EXPECT_FALSE(next_throughput(rules, {1, 1, 1}, {1, 1, 1}, 0, 0.5, next));
}

}  // namespace
}  // namespace raylane
