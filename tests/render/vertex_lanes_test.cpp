// What follows the BSDF in double lanes (render/vertex_lanes.h) against the scalar steps the
// double shading takes (shadow_contribution, next_throughput, offset_ray_origin with
// hit_point_error), bit for bit at every instruction set this CPU has, on random vertices and
// on the edges: no light point, f = 0, no sample, roulette's threshold, overflowing
// throughputs, normals along an axis (offsets of 0 in two components), points at 0 and −0,
// offsets that land on 0, infinite and NaN points, a NaN t, and points whose next origin lands
// on a midpoint between two floats (where the float origin shows the double step's direction).
#include "raylane/render/vertex_lanes.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
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

struct Vertex {
  glm::dvec3 beta{}, p{}, ng{}, o{}, d{};
  double t;
  glm::dvec3 light_wi{}, le{}, f{};
  double light_dist, light_pdf, bsdf_pdf;
  glm::dvec3 wi{}, value{};
  double pdf, u;
  int midpoints = 0;  // next-origin components placed on a midpoint between floats (below)
};

// The next ray's offset as offset_ray_origin computes it (core/ray_offset.cpp), before the step.
glm::dvec3 next_ray_offset(const Vertex& v) {
  const glm::dvec3 offset = v.ng * dot(abs(v.ng), hit_point_error(Rayd{v.o, v.d}, v.t));
  return dot(v.ng, v.wi) < 0 ? -offset : offset;
}

// Moves the point so that p + offset lands on a midpoint between two floats in each component
// where the double sum allows it exactly. The origin is then stepped one double ulp away from p
// and rounded to float: the step alone decides which of the two floats it becomes (without
// one, ties go to even), so a step missed or taken the wrong way shows in the float origin.
void place_next_origin_on_midpoints(Vertex& v) {
  const glm::dvec3 offset = next_ray_offset(v);
  for (int k = 0; k < 3; ++k) {
    if (offset[k] == 0) continue;
    const float f = float(v.p[k]);
    const double mid = (double(f) + double(std::nextafter(f, HUGE_VALF))) / 2;  // exact
    v.p[k] = mid - offset[k];
    v.midpoints += v.p[k] + offset[k] == mid;
  }
}

glm::dvec3 random_unit(Rng& rng) {
  return sample_uniform_sphere(rng.uniform(), rng.uniform());
}

// Scales over many decades, so that offsets and throughputs meet their rounding edges.
double spread(Rng& rng, double lo_exp, double hi_exp) {
  return std::pow(10.0, lo_exp + (hi_exp - lo_exp) * rng.uniform());
}

// The BSDF's answers are float (render/materials/shade_lanes.h): the values rounded to it. Through a
// volatile: GCC 12's SLP vectoriser dropped the double → float → double round trip of a
// vector's components (seen in src/trace/tracer.cpp too).
double to_float(double x) {
  volatile float f = float(x);
  return f;
}
glm::dvec3 to_float(const glm::dvec3& v) {
  return {to_float(v.x), to_float(v.y), to_float(v.z)};
}

Vertex random_vertex(Rng& rng, int i) {
  Vertex v;
  v.beta = glm::dvec3(rng.uniform(), rng.uniform(), rng.uniform()) * spread(rng, -3, 3);
  v.d = random_unit(rng);
  v.o = random_unit(rng) * spread(rng, -2, 4);
  v.t = spread(rng, -6, 3);
  v.p = i % 17 == 0 ? glm::dvec3(0, 0, 0) : v.o + v.d * v.t;
  v.ng = i % 5 == 0 ? glm::dvec3(0, i % 2 ? 1.0 : -1.0, 0) : random_unit(rng);
  v.light_wi = random_unit(rng);
  v.light_dist = i % 37 == 0 ? std::numeric_limits<double>::infinity() : spread(rng, -4, 4);
  v.le = glm::dvec3(1, 2, 3) * spread(rng, -1, 2);
  v.f = i % 13 == 0 ? glm::dvec3(0, 0, 0) : to_float(glm::dvec3(rng.uniform(), rng.uniform(), 0.5));
  v.light_pdf = i % 11 == 0 ? 0.0 : spread(rng, -3, 3);
  if (i % 97 == 0) v.light_pdf = 1e-320;  // a contribution that overflows
  v.bsdf_pdf = i % 7 == 0 ? 0.0 : to_float(spread(rng, -3, 3));
  v.wi = to_float(random_unit(rng));
  v.value = i % 19 == 0 ? glm::dvec3(0, 0, 0)
                        : to_float(glm::dvec3(rng.uniform(), rng.uniform(), rng.uniform()));
  v.pdf = i % 23 == 0 ? 0.0 : to_float(spread(rng, -3, 3));
  if (i % 89 == 0) {  // a throughput that overflows
    v.pdf = std::numeric_limits<float>::denorm_min();
    v.beta = v.beta * 1e300;
  }
  v.u = i % 29 == 0 ? 0.8 : rng.uniform();  // roulette's threshold itself ends the path
  if (i % 31 == 0) {
    // The offset lands exactly on 0: the origin must still step off it (to the least denormal).
    v.ng = {1, 0, 0};
    v.light_wi = v.wi = to_float(normalize(glm::dvec3(1, 0.5, -0.5)));
    v.p.x = -hit_point_error(Rayd{v.o, v.d}, v.t).x;
  }
  // Points off the end of the doubles: infinite, or not a number (one or the other: where two
  // NaNs meet in a sum, which one's sign survives depends on the operands' order, which the
  // compiler may swap).
  const double inf = std::numeric_limits<double>::infinity();
  if (i % 43 == 0)
    v.p[i % 3] = i % 2 ? inf : -inf;
  else if (i % 47 == 0)
    v.p[i % 3] = std::numeric_limits<double>::quiet_NaN();
  else if (i % 59 == 0) {
    // A point at −0 on a face along an axis: the offset's zero components (±0, turned with the
    // side) decide the signs of the origin's zeros.
    v.p = {-0.0, v.p.y, -0.0};
    v.ng = {0, i % 2 ? 1.0 : -1.0, 0};
  } else if (i % 61 == 0)
    v.t = std::numeric_limits<double>::quiet_NaN();  // no bound on the point's error: NaN
  else if (i % 3 == 1 && i % 31 != 0)
    place_next_origin_on_midpoints(v);
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
      vb.ray_o[k][i] = v.o[k], vb.ray_d[k][i] = v.d[k];
      q.cones.wi[k][i] = v.light_wi[k], q.le[k][i] = v.le[k];
      sb.light_f[k][i] = float(v.f[k]), sb.wi[k][i] = float(v.wi[k]);
      sb.value[k][i] = float(v.value[k]);
    }
    const VertexRules row_rules = rules_of_row(rules, mixed, i);
    vb.t[i] = v.t, vb.u_roulette[i] = v.u;
    vb.survival[i] = row_rules.roulette ? row_rules.survival : 1.0;
    q.cones.dist[i] = v.light_dist, q.cones.pdf[i] = v.light_pdf;
    sb.light_pdf[i] = float(v.bsdf_pdf), sb.pdf[i] = float(v.pdf);
  }
}

glm::dvec3 row(const VertexBatch::Columns3& c, std::size_t i) {
  return {c[0][i], c[1][i], c[2][i]};
}
glm::vec3 row(const VertexBatch::FloatColumns3& c, std::size_t i) {
  return {c[0][i], c[1][i], c[2][i]};
}

// Counts of what the rows exercised, so the test can require every branch.
struct Seen {
  int shadows = 0, no_shadow = 0, alive = 0, ended = 0, environment = 0, midpoints = 0;
};

void expect_rows_are_scalar(const VertexRules& batch_rules, bool mixed,
                            const std::vector<Vertex>& vs, const VertexBatch& b, Seen& seen) {
  int failures = 0;
  for (std::size_t i = 0; i < vs.size() && failures < 10; ++i) {
    const Vertex& v = vs[i];
    const VertexRules rules = rules_of_row(batch_rules, mixed, i);
    Rayd ray{v.o, v.d};
    glm::dvec3 err = hit_point_error(ray, v.t);
    glm::dvec3 c{};
    bool shadow = shadow_contribution(rules, v.beta, v.f, v.le, v.light_pdf, v.bsdf_pdf, c);
    bool ok = (b.shadow_ok[i] != 0) == shadow;
    if (shadow) {
      const glm::dvec3 o = offset_ray_origin(v.p, err, v.ng, v.light_wi);
      // The origin and end rounded to float as ray_cast<float> rounds them.
      ok = ok && same_bits(row(b.shadow_c, i), c) && same_bits(row(b.shadow_o, i), glm::vec3(o)) &&
           same_bits(b.shadow_tmax[i], float(shadow_ray_tmax(o, v.p, v.light_wi, v.light_dist)));
      seen.environment += std::isinf(v.light_dist);
    }
    glm::dvec3 next{};
    bool alive = next_throughput(rules, v.beta, v.value, v.pdf, v.u, next);
    ok = ok && (b.alive[i] != 0) == alive;
    if (alive) {
      ok = ok && same_bits(row(b.next_beta, i), next) &&
           same_bits(row(b.next_o, i), glm::vec3(offset_ray_origin(v.p, err, v.ng, v.wi)));
      seen.midpoints += v.midpoints;
    }
    failures += !ok;
    EXPECT_TRUE(ok) << "row " << i << ": shadow " << shadow << " alive " << alive;
    ++(shadow ? seen.shadows : seen.no_shadow);
    ++(alive ? seen.alive : seen.ended);
  }
}

TEST(VertexLanes, ShadowRaysAndNextRaysAreTheScalarOnes) {
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
        EXPECT_GT(seen.midpoints, 3000);
        // Without lights: no shadow ray anywhere, the same next rays.
        VertexBatch with_lights = b.vertex;
        finish_vertices(isa, rules, b.bsdf, nullptr, b.vertex);
        for (std::size_t i = 0; i < vs.size(); ++i) {
          ASSERT_EQ(b.vertex.shadow_ok[i], 0.0) << "row " << i;
          ASSERT_EQ(b.vertex.alive[i], with_lights.alive[i]) << "row " << i;
          if (b.vertex.alive[i] != 0) {
            ASSERT_TRUE(same_bits(row(b.vertex.next_beta, i), row(with_lights.next_beta, i)) &&
                        same_bits(row(b.vertex.next_o, i), row(with_lights.next_o, i)))
                << "row " << i;
          }
        }
      }
}

// The scalar steps themselves, on values whose answers are known.
TEST(VertexLanes, ScalarStepsOnKnownValues) {
  VertexRules rules{true, true, 0.8};
  glm::dvec3 c{};
  // Equal densities: the power heuristic weighs 1/2; beta·f·Le·(1/2)/2.
  ASSERT_TRUE(shadow_contribution(rules, {1, 2, 4}, {0.5, 0.5, 0.5}, {2, 2, 2}, 2, 2, c));
  EXPECT_EQ(c, glm::dvec3(0.25, 0.5, 1));
  EXPECT_FALSE(shadow_contribution(rules, {1, 1, 1}, {0, 0, 0}, {1, 1, 1}, 1, 1, c));
  EXPECT_FALSE(shadow_contribution(rules, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}, 0, 1, c));
  glm::dvec3 next{};
  ASSERT_TRUE(next_throughput(rules, {1, 1, 1}, {0.4, 0.8, 1.6}, 0.5, 0.5, next));
  EXPECT_EQ(next, glm::dvec3(0.4 / 0.5 / 0.8, 0.8 / 0.5 / 0.8, 1.6 / 0.5 / 0.8));
  EXPECT_FALSE(next_throughput(rules, {1, 1, 1}, {1, 1, 1}, 1, 0.8, next));  // roulette ends it
  rules.roulette = false;
  ASSERT_TRUE(next_throughput(rules, {1, 1, 1}, {1, 1, 1}, 1, 0.9, next));
  EXPECT_EQ(next, glm::dvec3(1, 1, 1));
  EXPECT_FALSE(next_throughput(rules, {1, 1, 1}, {1, 1, 1}, 0, 0.5, next));
}

// filter_rows keeps the rows whose flag is not 0, in order, in every 4- and 8-byte column, at
// every instruction set: for batches of every length from 0 to 70 (whole lane batches and a
// tail), flags all on, all off, alternating, in runs and at random, NaN payloads and −0
// carried as bits. Nothing at or past the batch's rows is written.
TEST(VertexLanes, FilterRowsKeepsTheFlaggedRowsInOrder) {
  Rng rng(5);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    for (std::size_t n = 0; n <= 70; ++n)
      for (int pattern = 0; pattern < 5; ++pattern) {
        std::vector<double> keep(n), wide(n);
        std::vector<float> narrow(n);
        std::vector<uint32_t> index(n);
        for (std::size_t r = 0; r < n; ++r) {
          const bool on = pattern == 0   ? true
                          : pattern == 1 ? false
                          : pattern == 2 ? r % 2 == 0
                          : pattern == 3 ? (r / 5) % 2 == 1
                                         : rng.uniform() < 0.7;
          keep[r] = on ? 1.0 : 0.0;
          narrow[r] = r % 7 == 3 ? -0.0f : float(rng.uniform()) - 0.5f;
          wide[r] = r % 11 == 4 ? std::bit_cast<double>(0x7ff8000000001234ull) : rng.uniform();
          index[r] = uint32_t(rng.uniform() * 4e9);
        }
        const uint32_t canary = 0xdeadbeefu;
        const std::size_t room = n + 20;
        std::vector<float> narrow_out(room, std::bit_cast<float>(canary));
        std::vector<uint32_t> index_out(room, canary);
        std::vector<double> wide_out(room, std::bit_cast<double>(uint64_t(canary)));
        RowFilter f;
        f.keep = keep.data();
        f.add(narrow.data(), narrow_out.data());
        f.add(index.data(), index_out.data());
        f.add(wide.data(), wide_out.data());
        const std::size_t kept = filter_rows(isa, f, n);
        std::size_t m = 0;
        for (std::size_t r = 0; r < n; ++r) {
          if (keep[r] == 0) continue;
          ASSERT_EQ(std::bit_cast<uint32_t>(narrow_out[m]), std::bit_cast<uint32_t>(narrow[r]))
              << "n " << n << " pattern " << pattern << " row " << r;
          ASSERT_EQ(index_out[m], index[r]) << "n " << n << " row " << r;
          ASSERT_EQ(std::bit_cast<uint64_t>(wide_out[m]), std::bit_cast<uint64_t>(wide[r]))
              << "n " << n << " pattern " << pattern << " row " << r;
          ++m;
        }
        ASSERT_EQ(kept, m) << "n " << n << " pattern " << pattern;
        for (std::size_t r = n; r < room; ++r) {
          ASSERT_EQ(std::bit_cast<uint32_t>(narrow_out[r]), canary) << "past the rows";
          ASSERT_EQ(index_out[r], canary) << "past the rows";
          ASSERT_EQ(std::bit_cast<uint64_t>(wide_out[r]), uint64_t(canary)) << "past the rows";
        }
      }
  }
}

// gather_vertex_rays puts row r's ray, the stream's ray rows[r], into the batches: origin and
// direction widened exactly, the direction turned around in float, bit for bit (−0 and NaN
// payloads too), at every instruction set: for every row count from 0 to 45, with rows in runs
// (whole-batch loads), backward, repeated and at random (gathers), and runs of 17 broken by others
// (both in one call at every width; the runs end at the stream's last ray). The rows past n
// keep what they held.
TEST(VertexLanes, GatherVertexRaysGivesEachRowItsStreamRay) {
  Rng rng(9);
  RayStream rays;
  const std::size_t kRays = 200;
  rays.resize(kRays);
  Column<float>* columns[6] = {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz};
  for (std::size_t i = 0; i < kRays; ++i)
    for (int c = 0; c < 6; ++c)
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
        VertexBatch vertices;
        ShadeBatch shade;
        vertices.resize(n + 9), shade.resize(n + 9);
        const double unwritten = -7;
        for (int k = 0; k < 3; ++k) {
          std::fill(vertices.ray_o[k].begin(), vertices.ray_o[k].end(), unwritten);
          std::fill(vertices.ray_d[k].begin(), vertices.ray_d[k].end(), unwritten);
          std::fill(shade.wo[k].begin(), shade.wo[k].end(), float(unwritten));
        }
        gather_vertex_rays(isa, rays, rows.data(), n, vertices, shade);
        for (std::size_t r = 0; r < n + 9; ++r)
          for (int k = 0; k < 3; ++k) {
            const bool row = r < n;
            const float o = row ? (*columns[k])[rows[r]] : 0,
                        d = row ? (*columns[3 + k])[rows[r]] : 0;
            ASSERT_TRUE(same_bits(vertices.ray_o[k][r], row ? double(o) : unwritten) &&
                        same_bits(vertices.ray_d[k][r], row ? double(d) : unwritten) &&
                        same_bits(shade.wo[k][r], row ? -d : float(unwritten)))
                << "n " << n << " pattern " << pattern << " row " << r << " axis " << k;
          }
      }
  }
}

}  // namespace
}  // namespace raylane
