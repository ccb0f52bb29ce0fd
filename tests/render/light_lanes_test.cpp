// Sphere lights' cones in double lanes (render/light_lanes.h) against the scalar
// Sphere::sample_subtended they transcribe, bit for bit at every instruction set this CPU has,
// and LightSampler::sample_many against sample() on a scene with every kind of light.
#include "raylane/render/light_lanes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "raylane/core/strings.h"
#include "raylane/core/warps.h"
#include "raylane/render/lights.h"
#include "raylane/render/rng.h"
#include "raylane/scene/parser.h"
#include "support/same_bits.h"

namespace raylane {
namespace {

// The lanes must give the scalar results bit for bit (support/same_bits.h).
using testing::same_bits;

struct Case {
  glm::dvec3 ref{};
  uint32_t sphere;
  double u1, u2;
};

// Random spheres (radii from 1e-6 to 10) seen from 1 + 1e-9 radii away out to 100 radii, and
// from inside; the warp's numbers include the ends of [0, 1] and the quarter turns.
std::vector<Case> random_cases(SphereTable& spheres, int count, uint64_t seed) {
  Rng rng(seed);
  std::vector<Case> cases;
  const double edge[] = {0, 0.25, 0.5, 0.75, 1 - 0x1p-53};
  for (int i = 0; i < count; ++i) {
    double r = std::pow(10.0, -6 + 7 * rng.uniform());
    double c[4] = {20 * rng.uniform() - 10, 20 * rng.uniform() - 10, 20 * rng.uniform() - 10, r};
    EXPECT_FALSE(spheres.append(std::span<const double, 4>(c, 4), 0).has_value());
    uint32_t row = uint32_t(spheres.size() - 1);
    double gap = i % 10 == 0 ? -rng.uniform() : std::pow(10.0, -9 + 11 * rng.uniform());
    glm::dvec3 dir = sample_uniform_sphere(rng.uniform(), rng.uniform());
    glm::dvec3 center(spheres.center(row));
    double rr = spheres.r[row];
    double u1 = i % 7 == 0 ? edge[i % 5] : rng.uniform();
    double u2 = i % 3 == 0 ? edge[(i / 3) % 5] : rng.uniform();
    cases.push_back({center + dir * (rr * (1 + gap)), row, u1, u2});
  }
  return cases;
}

ConeBatch batch_of(const SphereTable& spheres, const std::vector<Case>& cases) {
  ConeBatch b;
  b.resize(cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    for (int k = 0; k < 3; ++k)
      b.ref[k][i] = c.ref[k], b.center[k][i] = spheres.center(c.sphere)[k];
    b.radius[i] = spheres.r[c.sphere], b.u1[i] = c.u1, b.u2[i] = c.u2;
    b.choice[i] = i % 2 == 0 ? 1.0 : 0.3;  // a light among others: pdf is a true division
  }
  return b;
}

TEST(LightLanes, ConesAreTheScalarSphereSamples) {
  SphereTable spheres;
  std::vector<Case> cases = random_cases(spheres, 20000, 7);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(cat("isa ", isa_name(isa)));
    ConeBatch b = batch_of(spheres, cases);
    sample_cones(isa, b);
    int outside = 0, failures = 0;
    for (std::size_t i = 0; i < cases.size() && failures < 10; ++i) {
      const Case& c = cases[i];
      auto s = Sphere::sample_subtended(spheres, c.sphere, c.ref, c.u1, c.u2);
      if (!s) {
        failures += !(b.solid_angle[i] == 0 && b.pdf[i] == 0);
        EXPECT_EQ(b.solid_angle[i], 0) << "row " << i << " is inside its sphere";
        EXPECT_EQ(b.pdf[i], 0) << "row " << i << " is inside its sphere";
        continue;
      }
      ++outside;
      glm::dvec3 wi(b.wi[0][i], b.wi[1][i], b.wi[2][i]);
      bool ok = same_bits(wi, s->wi) && same_bits(b.dist[i], s->dist) &&
                same_bits(b.solid_angle[i], s->solid_angle) &&
                same_bits(b.pdf[i], b.choice[i] / s->solid_angle);
      failures += !ok;
      EXPECT_TRUE(ok) << "row " << i << ": lanes wi " << wi.x << " " << wi.y << " " << wi.z
                      << " dist " << b.dist[i] << " solid " << b.solid_angle[i] << "; scalar wi "
                      << s->wi.x << " " << s->wi.y << " " << s->wi.z << " dist " << s->dist
                      << " solid " << s->solid_angle;
    }
    EXPECT_GT(outside, 15000);  // most rows sample the cone; about a tenth are inside
  }
}

// A scene with a sphere, a box, a cylinder and a triangle light (the last two by area), and
// shading points around them, some inside the sphere light (by area too).
TEST(LightLanes, SampleManyIsSampleForEveryQuery) {
  auto parsed = parse_scene(
      "camera 0 0 0 1\nlight 5 5 5\nsphere 0 3 0 0.5\nlight 1 2 3\nbox 2 2 2 1 0.5 0.25\n"
      "light 2 2 2\ncylinder -2 1 0 0 1 0 0.3\nbrdf 0.5 0.5 0.5 0 0 0 1\nsphere 0 -1 0 0.2\n",
      "lights.scn");
  ASSERT_TRUE(parsed.ok());
  LightSampler lights(parsed.scene);
  Rng rng(3);
  LightQueries q;
  q.resize(4000);
  for (std::size_t i = 0; i < q.size(); ++i) {
    glm::dvec3 ref = i % 20 == 0 ? glm::dvec3(0, 3, 0.1 * rng.uniform())
                                 : glm::dvec3(8 * rng.uniform() - 4, 8 * rng.uniform() - 4,
                                              8 * rng.uniform() - 4);
    for (int k = 0; k < 3; ++k)
      q.cones.ref[k][i] = ref[k];
    q.cones.u1[i] = rng.uniform(), q.cones.u2[i] = rng.uniform();
    q.u_light[i] = rng.uniform(), q.u_part[i] = rng.uniform();
  }
  int kinds_seen[4] = {};
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(cat("isa ", isa_name(isa)));
    lights.sample_many(isa, q);
    for (std::size_t i = 0; i < q.size(); ++i) {
      LightSample want =
          lights.sample(q.ref(i), q.u_light[i], q.u_part[i], q.cones.u1[i], q.cones.u2[i]);
      ASSERT_EQ(q.light[i], want.light) << "query " << i;
      ASSERT_EQ(q.valid(i), want.valid()) << "query " << i;
      ++kinds_seen[std::size_t(q.light[i].tag())];
      if (!want.valid()) continue;
      glm::dvec3 le(q.le[0][i], q.le[1][i], q.le[2][i]);
      EXPECT_EQ(le, want.le);
      // The point is ref + wi·dist for a cone's sample, so these pin it down too.
      EXPECT_TRUE(same_bits(q.wi(i), want.wi) && same_bits(q.pdf(i), want.pdf) &&
                  same_bits(q.cones.dist[i], want.dist))
          << "query " << i;
    }
  }
  for (int k = 0; k < 3; ++k)
    EXPECT_GT(kinds_seen[k], 0) << "no query picked a light of kind " << k;
}

// The render computes only the numbers numbers_read() names (render/wavefront/lane_vertices.cpp):
// the others must change nothing sample() returns, and the count must be what each scene needs.
TEST(LightLanes, NumbersReadAreAllSamplingReads) {
  const char* kScenes[][2] = {
      {"light 1 1 1\nsphere 0 3 0 0.5\n", "2"},
      {"light 1 1 1\nsphere 0 3 0 0.5\nsphere 2 3 0 0.25\n", "3"},
      {"light 1 1 1\nsphere 0 3 0 0.5\nbox 2 2 2 1 0.5 0.25\n", "4"},
      {"light 1 1 1\nbox 2 2 2 1 0.5 0.25\n", "4"},
  };
  for (const auto& [text, want] : kScenes) {
    SCOPED_TRACE(text);
    auto parsed =
        parse_scene(cat("camera 0 0 0 1\n", text, "brdf 0.5 0.5 0.5 0 0 0 1\n"), "numbers.scn");
    ASSERT_TRUE(parsed.ok());
    LightSampler lights(parsed.scene);
    const int read = lights.numbers_read();
    EXPECT_EQ(read, want[0] - '0');
    Rng rng(11);
    for (int i = 0; i < 2000; ++i) {
      glm::dvec3 ref(8 * rng.uniform() - 4, 8 * rng.uniform() - 4, 8 * rng.uniform() - 4);
      double u[4] = {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
      LightSample a = lights.sample(ref, u[2], u[3], u[0], u[1]);
      for (int c = read; c < 4; ++c)
        u[c] = rng.uniform();  // what an unread number holds does not matter
      LightSample b = lights.sample(ref, u[2], u[3], u[0], u[1]);
      ASSERT_EQ(a.light, b.light) << "sample " << i;
      ASSERT_TRUE(same_bits(a.wi, b.wi) && same_bits(a.pdf, b.pdf)) << "sample " << i;
    }
  }
}

}  // namespace
}  // namespace raylane
