// What follows the BSDF in float lanes (render/vertex_lanes.h) against the same steps' scalar
// float instance (shadow_contribution<float>, next_throughput<float>, offset_origin<float> with
// float_hit_point_bound<float>, shadow_tmax<float>), bit for bit at every instruction set this CPU
// has, on random vertices and on the edges: no light point, f = 0, no sample, roulette's
// threshold, overflowing throughputs and densities, normals along an axis (offsets of 0 in two
// components), points at 0 and −0, offsets that land on 0, points at ±FLT_MAX and the least
// denormals, infinite and NaN points, a NaN t.
// scatter_vertices (the BSDF and these steps in one pass) against shade_lanes then
// finish_vertices.
#include "raylane/render/vertex_lanes.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "raylane/core/ray_offset.h"
#include "raylane/core/strings.h"
#include "raylane/core/warps.h"
#include "raylane/render/samplers/rng.h"
#include "support/same_bits.h"

namespace raylane {
namespace {

// The lanes must give the scalar results bit for bit (support/same_bits.h).
using testing::same_bits;
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

Vec random_unit(Rng& rng) {
  return Vec(sample_uniform_sphere(rng.uniform(), rng.uniform()));
}

// Scales over many decades, so that offsets and throughputs meet their rounding edges.
double spread(Rng& rng, double lo_exp, double hi_exp) {
  return std::pow(10.0, lo_exp + (hi_exp - lo_exp) * rng.uniform());
}

Vec bound_of(const Vertex& v) {
  return float_hit_point_bound<float>(v.o, v.d, v.t, v.p);
}

// The x component of the offset (core/ray_offset.h's offset_origin), before its step.
float offset_x(const Vertex& v) {
  const Vec e = bound_of(v);
  return v.ng.x * (std::abs(v.ng.x) * e.x + std::abs(v.ng.y) * e.y + std::abs(v.ng.z) * e.z);
}

Vertex random_vertex(Rng& rng, int i) {
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
VertexRules rules_of_row(const VertexRules& rules, bool mixed, std::size_t i) {
  VertexRules r = rules;
  if (mixed && i % 3 == 0) r.roulette = false;
  return r;
}

void fill(Batches& b, const std::vector<Vertex>& vs, const VertexRules& rules, bool mixed) {
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
bool same_or_nan(float a, float b) {
  return same_bits(a, b) || (std::isnan(a) && std::isnan(b));
}
bool same_origin(const Vec& a, const Vec& b) {
  return same_or_nan(a.x, b.x) && same_or_nan(a.y, b.y) && same_or_nan(a.z, b.z);
}

// Counts of what the rows exercised, so the test can require every branch.
struct Seen {
  int shadows = 0, no_shadow = 0, alive = 0, ended = 0, environment = 0, zero_sums = 0;
};

void expect_rows_are_scalar(const VertexRules& batch_rules, bool mixed,
                            const std::vector<Vertex>& vs, const VertexBatch& b, Seen& seen) {
  int failures = 0;
  for (std::size_t i = 0; i < vs.size() && failures < 10; ++i) {
    const Vertex& v = vs[i];
    const VertexRules rules = rules_of_row(batch_rules, mixed, i);
    const Vec err = bound_of(v);
    seen.zero_sums += v.p.x + offset_x(v) == 0 && offset_x(v) != 0;
    Vec c{};
    const float light_pdf = float(v.light_pdf), dist = float(v.light_dist);
    const bool shadow =
        shadow_contribution<float>(rules, v.beta, v.f, Vec(v.le), light_pdf, v.bsdf_pdf, c);
    bool ok = (b.shadow_ok[i] != 0) == shadow;
    if (shadow) {
      const Vec o = offset_origin<float>(v.p, err, v.ng, v.light_wi);
      ok = ok && same_bits(row(b.shadow_c, i), glm::dvec3(c)) &&
           same_origin(row(b.shadow_o, i), o) &&
           same_or_nan(b.shadow_tmax[i], shadow_tmax<float>(o, v.p, v.light_wi, dist));
      seen.environment += std::isinf(v.light_dist);
    }
    Vec next{};
    const bool alive = next_throughput<float>(rules, v.beta, v.value, v.pdf, v.u, next);
    ok = ok && (b.alive[i] != 0) == alive;
    if (alive)
      ok = ok && same_bits(row(b.next_beta, i), next) &&
           same_origin(row(b.next_o, i), offset_origin<float>(v.p, err, v.ng, v.wi));
    failures += !ok;
    EXPECT_TRUE(ok) << "row " << i << ": shadow " << shadow << " alive " << alive;
    ++(shadow ? seen.shadows : seen.no_shadow);
    ++(alive ? seen.alive : seen.ended);
  }
}

TEST(VertexLanes, ShadowRaysAndNextRaysAreTheScalarFloatSteps) {
  Rng rng(11);
  std::vector<Vertex> vs;
  // 20003: not a multiple of any lane width, so the last batch reads the columns' padding.
  for (int i = 0; i < 20003; ++i)
    vs.push_back(random_vertex(rng, i));
  for (Isa isa : supported_isas())
    for (bool mis : {false, true})
      for (int roulette : {0, 1, 2}) {  // none, every row, two rows in three
        SCOPED_TRACE(cat("isa ", isa_name(isa), " mis ", mis, " roulette ", roulette));
        const VertexRules rules{mis, roulette > 0, 0.8};
        const bool mixed = roulette == 2;
        Batches b;
        fill(b, vs, rules, mixed);
        finish_vertices(isa, rules, b.bsdf, &b.lights, b.vertex);
        Seen seen;
        expect_rows_are_scalar(rules, mixed, vs, b.vertex, seen);
        EXPECT_GT(seen.shadows, 10000);
        EXPECT_GT(seen.environment, 200);
        EXPECT_GT(seen.no_shadow, 2000);
        EXPECT_GT(seen.alive, 10000);
        EXPECT_GT(seen.ended, roulette == 1 ? 4000 : roulette == 2 ? 3000 : 1000);
        EXPECT_GT(seen.zero_sums, 300);  // offsets landing on 0, stepped to the least denormal
        // Without lights: no shadow ray anywhere, the same next rays.
        VertexBatch with_lights = b.vertex;
        finish_vertices(isa, rules, b.bsdf, nullptr, b.vertex);
        for (std::size_t i = 0; i < vs.size(); ++i) {
          ASSERT_EQ(b.vertex.shadow_ok[i], 0.0f) << "row " << i;
          ASSERT_EQ(b.vertex.alive[i], with_lights.alive[i]) << "row " << i;
          if (b.vertex.alive[i] != 0) {
            ASSERT_TRUE(same_bits(row(b.vertex.next_beta, i), row(with_lights.next_beta, i)) &&
                        same_bits(row(b.vertex.next_o, i), row(with_lights.next_o, i)))
                << "row " << i;
          }
        }
      }
}

// The steps at double on values whose answers are known.
TEST(VertexLanes, ScalarStepsOnKnownValues) {
  VertexRules rules{true, true, 0.8};
  glm::dvec3 c{};
  // Equal densities: the power heuristic weighs 1/2; beta·f·Le·(1/2)/2.
  ASSERT_TRUE(shadow_contribution<double>(rules, {1, 2, 4}, {0.5, 0.5, 0.5}, {2, 2, 2}, 2, 2, c));
  EXPECT_EQ(c, glm::dvec3(0.25, 0.5, 1));
  EXPECT_FALSE(shadow_contribution<double>(rules, {1, 1, 1}, {0, 0, 0}, {1, 1, 1}, 1, 1, c));
  EXPECT_FALSE(shadow_contribution<double>(rules, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}, 0, 1, c));
  // Densities whose squares leave float's range weigh as their ratio says: 1/(1 + 1/4) and
  // 1/(1 + 4), not inf/inf.
  EXPECT_EQ(power_heuristic<float>(2e30f, 1e30f), 0.8f);
  EXPECT_EQ(power_heuristic<float>(1e-30f, 2e-30f), 0.2f);
  glm::dvec3 next{};
  ASSERT_TRUE(next_throughput<double>(rules, {1, 1, 1}, {0.4, 0.8, 1.6}, 0.5, 0.5, next));
  EXPECT_EQ(next, glm::dvec3(0.4 / 0.5 / 0.8, 0.8 / 0.5 / 0.8, 1.6 / 0.5 / 0.8));
  EXPECT_FALSE(next_throughput<double>(rules, {1, 1, 1}, {1, 1, 1}, 1, 0.8, next));  // roulette
  rules.roulette = false;
  ASSERT_TRUE(next_throughput<double>(rules, {1, 1, 1}, {1, 1, 1}, 1, 0.9, next));
  EXPECT_EQ(next, glm::dvec3(1, 1, 1));
  EXPECT_FALSE(next_throughput<double>(rules, {1, 1, 1}, {1, 1, 1}, 0, 0.5, next));
}

// A scatter kernel's queues, each destination with `room` values and canaries after them.
struct Queues {
  static constexpr uint32_t kCanary = 0xdeadbeefu;
  std::array<std::vector<float>, 3> next_o, next_d, shadow_o, shadow_d, next_prev_p;
  std::vector<float> shadow_tmax;
  std::vector<uint32_t> next_path, shadow_path, shadow_light, next_depth;
  std::array<std::vector<double>, 3> shadow_c, next_beta;
  std::vector<double> next_prev_pdf;
  std::size_t room;
  VertexQueues q;

  Queues(std::size_t room, std::size_t canaries, const uint32_t* path, const uint32_t* depth)
      : room(room) {
    const std::size_t n = room + canaries;
    const float f = std::bit_cast<float>(kCanary);
    const double d = std::bit_cast<double>(uint64_t(kCanary));
    for (auto* c : {&next_o, &next_d, &shadow_o, &shadow_d, &next_prev_p})
      for (std::size_t k = 0; k < 3; ++k)
        (*c)[k].assign(n, f);
    shadow_tmax.assign(n, f);
    for (auto* c : {&next_path, &shadow_path, &shadow_light, &next_depth})
      c->assign(n, kCanary);
    for (auto* c3 : {&shadow_c, &next_beta})
      for (auto& c : *c3)
        c.assign(n, d);
    next_prev_pdf.assign(n, d);
    q.path = path, q.depth = depth;
    for (std::size_t k = 0; k < 3; ++k) {
      q.next_o[k] = next_o[k].data(), q.next_d[k] = next_d[k].data();
      q.shadow_o[k] = shadow_o[k].data(), q.shadow_d[k] = shadow_d[k].data();
      q.shadow_c[k] = shadow_c[k].data(), q.next_beta[k] = next_beta[k].data();
      q.next_prev_p[k] = next_prev_p[k].data();
    }
    q.next_path = next_path.data(), q.shadow_path = shadow_path.data();
    q.shadow_light = shadow_light.data(), q.shadow_tmax = shadow_tmax.data();
    q.next_prev_pdf = next_prev_pdf.data(), q.next_depth = next_depth.data();
  }
  // Whether every value at or past `room` is still its canary.
  bool canaries_alive() const {
    bool alive = true;
    for (std::size_t r = room; r < next_path.size(); ++r) {
      for (const auto* c : {&next_o, &next_d, &shadow_o, &shadow_d, &next_prev_p})
        for (std::size_t k = 0; k < 3; ++k)
          alive = alive && std::bit_cast<uint32_t>((*c)[k][r]) == kCanary;
      for (std::size_t k = 0; k < 3; ++k)
        alive = alive && std::bit_cast<uint64_t>(shadow_c[k][r]) == uint64_t(kCanary) &&
                std::bit_cast<uint64_t>(next_beta[k][r]) == uint64_t(kCanary);
      alive = alive && std::bit_cast<uint32_t>(shadow_tmax[r]) == kCanary &&
              next_path[r] == kCanary && shadow_path[r] == kCanary && shadow_light[r] == kCanary &&
              next_depth[r] == kCanary &&
              std::bit_cast<uint64_t>(next_prev_pdf[r]) == uint64_t(kCanary);
    }
    return alive;
  }
};

// The kernel's queues are finish_vertices' columns (after shade_lanes) filtered by its flags, in
// row order, bit for bit (an origin or end that is NaN in both may differ in its sign:
// same_or_nan); a next ray carries the new throughput and the BSDF's density widened, the
// vertex's point and the depth after the row's.
void expect_queues_are_the_flagged_rows(const Batches& apart, const std::vector<uint32_t>& path,
                                        const std::vector<uint32_t>& depth, std::size_t n,
                                        bool lights, const Queues& got) {
  const VertexBatch& y = apart.vertex;
  std::size_t next = 0, shadows = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (lights && y.shadow_ok[i] != 0) {
      const std::size_t m = shadows++;
      ASSERT_TRUE(m < got.q.shadow_count && same_bits(row(got.shadow_c, m), row(y.shadow_c, i)) &&
                  same_origin(row(got.shadow_o, m), row(y.shadow_o, i)) &&
                  same_bits(row(got.shadow_d, m), row(apart.bsdf.light_wi, i)) &&
                  same_or_nan(got.shadow_tmax[m], y.shadow_tmax[i]) &&
                  got.shadow_light[m] == apart.lights.light[i].bits() &&
                  got.shadow_path[m] == path[i])
          << "shadow ray of row " << i;
    }
    if (y.alive[i] != 0) {
      const std::size_t m = next++;
      ASSERT_TRUE(m < got.q.next_count && same_origin(row(got.next_o, m), row(y.next_o, i)) &&
                  same_bits(row(got.next_d, m), row(apart.bsdf.wi, i)) &&
                  got.next_path[m] == path[i])
          << "next ray of row " << i;
      ASSERT_TRUE(same_bits(row(got.next_beta, m), glm::dvec3(row(y.next_beta, i))) &&
                  same_bits(row(got.next_prev_p, m), row(y.p, i)) &&
                  same_bits(got.next_prev_pdf[m], double(apart.bsdf.pdf[i])) &&
                  got.next_depth[m] == depth[i] + 1)
          << "what the next ray of row " << i << " carries";
    }
  }
  EXPECT_EQ(got.q.shadow_count, shadows);
  EXPECT_EQ(got.q.next_count, next);
  EXPECT_TRUE(got.canaries_alive()) << "a destination written at or past its room";
}

// n rows of random vertices in a batch, and its padding rows past n holding an earlier
// wavefront's vertices, as the render's do (the columns never shrink): rows to be queued
// nowhere, though they would go on.
Batches random_rows(Rng& rng, std::size_t n, const VertexRules& rules) {
  const std::size_t padded = (n + 15) / 16 * 16;
  std::vector<Vertex> vs;
  for (std::size_t i = 0; i < padded; ++i)
    vs.push_back(random_vertex(rng, int(i)));
  Batches b;
  fill(b, vs, rules, true);
  b.vertex.resize(n), b.bsdf.resize(n), b.lights.resize(n);
  return b;
}

// scatter_vertices is shade_lanes then finish_vertices, then a filter of their rows by their
// flags into the queues, bit for bit: the same BSDF answers, kept in registers instead of
// columns, and the rays packed as they are made. At every instruction set, for row counts from
// 0 to 40 (whole lane batches and partial last ones, whose padding lanes must queue nothing) and
// 5003, with and without lights; nothing written at or past the rows rounded up to 16.
TEST(VertexLanes, ScatterQueuesTheRaysOfTheBsdfAndTheStepsAfterIt) {
  std::vector<Material> materials(3);
  materials[0].kd = {0.5f, 0.4f, 0.3f};
  materials[1].kd = {0.2f, 0.2f, 0.2f}, materials[1].ks = {0.5f, 0.5f, 0.5f},
  materials[1].alpha = 40;
  materials[2].ks = {0.1f, 0.1f, 0.1f}, materials[2].kt = {0.9f, 0.9f, 0.9f},
  materials[2].alpha = 200, materials[2].ior = 1.5f;
  const LaneMaterials lanes(materials);
  Rng rng(23);
  std::vector<std::size_t> sizes;
  for (std::size_t n = 0; n <= 40; ++n)
    sizes.push_back(n);
  sizes.push_back(5003);
  for (Isa isa : supported_isas())
    for (std::size_t n : sizes)
      for (bool lights : {true, false}) {
        SCOPED_TRACE(cat(isa_name(isa), " rows ", n, " lights ", lights));
        const std::size_t padded = (n + 15) / 16 * 16;
        const VertexRules rules{true, true, 0.8};
        Batches b = random_rows(rng, n, rules);
        ShadeBatch& sb = b.bsdf;
        std::vector<uint32_t> path(padded), depth(padded);
        for (std::size_t i = 0; i < n; ++i) {
          const Vec nv = random_unit(rng);
          for (std::size_t k = 0; k < 3; ++k)
            sb.n[k][i] = nv[k];
          sb.material[i] = int32_t(i % 3);
          sb.u_lobe[i] = float(rng.uniform()), sb.u1[i] = float(rng.uniform());
          sb.u2[i] = float(rng.uniform());
          b.lights.light[i] = PrimRef::from_bits(uint32_t(rng.uniform() * 4e9));
          path[i] = uint32_t(rng.uniform() * 4e9), depth[i] = uint32_t(rng.uniform() * 70);
        }
        const LightQueries* with = lights ? &b.lights : nullptr;
        Batches apart = b;
        shade_lanes(isa, lanes, apart.bsdf);
        finish_vertices(isa, rules, apart.bsdf, with, apart.vertex);
        Queues got(padded, 20, path.data(), depth.data());
        scatter_vertices(isa, lanes, rules, b.bsdf, with, b.vertex, got.q);
        expect_queues_are_the_flagged_rows(apart, path, depth, n, lights, got);
        if (n == 5003) {
          EXPECT_GT(got.q.next_count, 1000u);
          if (lights) {
            EXPECT_GT(got.q.shadow_count, 1000u);
          }
        }
        if (!lights) {
          EXPECT_EQ(got.q.shadow_count, 0u);
        }
      }
}

// Whether two runs' queues hold the same bytes, canaries included.
bool same_queues(const Queues& a, const Queues& b) {
  auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0;
  };
  bool ok = a.q.next_count == b.q.next_count && a.q.shadow_count == b.q.shadow_count;
  for (std::size_t k = 0; k < 3; ++k)
    ok = ok && same(a.next_o[k], b.next_o[k]) && same(a.next_d[k], b.next_d[k]) &&
         same(a.shadow_o[k], b.shadow_o[k]) && same(a.shadow_d[k], b.shadow_d[k]) &&
         same(a.next_prev_p[k], b.next_prev_p[k]) && same(a.shadow_c[k], b.shadow_c[k]) &&
         same(a.next_beta[k], b.next_beta[k]);
  return ok && same(a.shadow_tmax, b.shadow_tmax) && same(a.next_path, b.next_path) &&
         same(a.shadow_path, b.shadow_path) && same(a.shadow_light, b.shadow_light) &&
         same(a.next_depth, b.next_depth) && same(a.next_prev_pdf, b.next_prev_pdf);
}

// A scene's one light as broadcast lanes (LightQueries::one_light) is its light and radiance
// in every row's columns: the same queues, byte for byte, at every instruction set, with the
// columns the broadcast leaves unread holding NaN and other lights.
TEST(VertexLanes, ScatterTakesOneLightAsColumnsFilledWithIt) {
  std::vector<Material> materials(2);
  materials[0].kd = {0.5f, 0.4f, 0.3f};
  materials[1].kd = {0.2f, 0.2f, 0.2f}, materials[1].ks = {0.5f, 0.5f, 0.5f},
  materials[1].alpha = 40;
  const LaneMaterials lanes(materials);
  const LightQueries::OneLight one{PrimRef::from_bits(0x12345u), {2.5f, 1.5f, 0.75f}};
  Rng rng(29);
  for (Isa isa : supported_isas())
    for (std::size_t n : {std::size_t(37), std::size_t(5003)}) {
      SCOPED_TRACE(cat(isa_name(isa), " rows ", n));
      const std::size_t padded = (n + 15) / 16 * 16;
      const VertexRules rules{true, true, 0.8};
      Batches columns = random_rows(rng, n, rules);
      std::vector<uint32_t> path(padded), depth(padded);
      for (std::size_t i = 0; i < n; ++i) {
        const Vec nv = random_unit(rng);
        for (std::size_t k = 0; k < 3; ++k)
          columns.bsdf.n[k][i] = nv[k];
        columns.bsdf.material[i] = int32_t(i % 2);
        columns.bsdf.u_lobe[i] = float(rng.uniform()), columns.bsdf.u1[i] = float(rng.uniform());
        columns.bsdf.u2[i] = float(rng.uniform());
        path[i] = uint32_t(i), depth[i] = uint32_t(i % 7);
      }
      Batches broadcast = columns;
      for (std::size_t i = 0; i < padded; ++i) {
        columns.lights.light[i] = one.light;
        broadcast.lights.light[i] = PrimRef::from_bits(uint32_t(i));
        for (std::size_t k = 0; k < 3; ++k) {
          columns.lights.le[k][i] = one.le[k];
          broadcast.lights.le[k][i] = std::numeric_limits<float>::quiet_NaN();
        }
      }
      broadcast.lights.one_light = one;
      Queues from_columns(padded, 20, path.data(), depth.data());
      Queues from_broadcast(padded, 20, path.data(), depth.data());
      scatter_vertices(isa, lanes, rules, columns.bsdf, &columns.lights, columns.vertex,
                       from_columns.q);
      scatter_vertices(isa, lanes, rules, broadcast.bsdf, &broadcast.lights, broadcast.vertex,
                       from_broadcast.q);
      EXPECT_GT(from_columns.q.shadow_count, n / 4);
      EXPECT_TRUE(same_queues(from_columns, from_broadcast));
    }
}

// gather_wo puts row r's direction turned around, the stream's ray rows[r]'s, into the BSDF's
// batch, bit for bit (−0 and NaN payloads too), at every instruction set: for every row count
// from 0 to 45, with rows in runs (whole-batch loads), backward, repeated and at random
// (gathers), and runs of 17 broken by others (both in one call at every width; the runs end at
// the stream's last ray). The rows past n keep what they held.
TEST(VertexLanes, GatherWoGivesEachRowItsStreamRaysDirectionTurnedAround) {
  Rng rng(9);
  RayStream rays;
  const std::size_t kRays = 200;
  rays.resize(kRays);
  Column<float>* columns[3] = {&rays.dx, &rays.dy, &rays.dz};
  for (std::size_t i = 0; i < kRays; ++i)
    for (int c = 0; c < 3; ++c)
      (*columns[c])[i] = i % 13 == 5   ? -0.0f
                         : i % 17 == 2 ? std::bit_cast<float>(0x7fc01234u)
                                       : float(rng.uniform() * 20 - 10);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    for (std::size_t n = 0; n <= 45; ++n)
      for (int pattern = 0; pattern < 4; ++pattern) {
        std::vector<uint32_t> rows(n);
        for (std::size_t r = 0; r < n; ++r)
          rows[r] = pattern == 0   ? uint32_t(3 + r)                                 // one run
                    : pattern == 1 ? uint32_t(kRays - 1 - r)                         // backward
                    : pattern == 2 ? uint32_t(rng.uniform() * kRays)                 // at random
                                   : uint32_t(r % 20 < 17 ? kRays - n + r : r / 2);  // runs broken
        ShadeBatch shade;
        shade.resize(n + 9);
        const float unwritten = -7;
        for (int k = 0; k < 3; ++k)
          std::fill(shade.wo[k].begin(), shade.wo[k].end(), unwritten);
        gather_wo(isa, rays, rows.data(), n, shade);
        for (std::size_t r = 0; r < n + 9; ++r)
          for (int k = 0; k < 3; ++k) {
            const bool row = r < n;
            const float d = row ? (*columns[k])[rows[r]] : 0;
            ASSERT_TRUE(same_bits(shade.wo[k][r], row ? -d : unwritten))
                << "n " << n << " pattern " << pattern << " row " << r << " axis " << k;
          }
      }
  }
}

}  // namespace
}  // namespace raylane
