// What follows the BSDF in float lanes (render/vertex_lanes.h) against the same steps' scalar
// float instance (shadow_contribution<float>, next_throughput<float>, offset_origin<float> with
// float_hit_point_bound<float>, shadow_tmax<float>), bit for bit at every instruction set this CPU
// has, on random vertices and on the edges: no light point, f = 0, no sample, roulette's
// threshold, overflowing throughputs and densities, normals along an axis (offsets of 0 in two
// components), points at 0 and −0, offsets that land on 0, points at ±FLT_MAX and the least
// denormals, infinite and NaN points, a NaN t.
// gather_wo against the stream's rays. scatter_vertices (the BSDF and these steps in one pass)
// is scatter_lanes_test's.
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
#include "support/vertex_rows.h"

namespace raylane {
namespace {

// The lanes must give the scalar results bit for bit (support/same_bits.h).
using namespace testing;  // same_bits, the random vertices (support/vertex_rows.h)

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
