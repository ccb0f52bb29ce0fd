// Sphere lights' cones in double lanes (render/lights/light_lanes.h) against the scalar
// Sphere::sample_subtended they transcribe, bit for bit at every instruction set this CPU has,
// and LightSampler::sample_many against sample() on a scene with every kind of light.
#include "raylane/render/lights/light_lanes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "raylane/core/strings.h"
#include "raylane/core/warps.h"
#include "raylane/render/lights/lights.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/scene/parser.h"
#include "support/paths.h"
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

// Every row about one sphere (ConeSphere) gives the answers of the same sphere in the columns,
// bit for bit, and the float directions (ConeBatch::wi_float) are wi rounded where pdf > 0 and
// 0 elsewhere; padding rows never get a direction.
TEST(LightLanes, ConesAboutOneSphereAreTheColumnsAnswers) {
  SphereTable spheres;
  std::vector<Case> cases = random_cases(spheres, 4001, 9);
  for (Case& c : cases)
    c.sphere = 3;  // the refs stay where they were: some inside sphere 3, most far outside
  const ConeSphere one{{spheres.center(3)[0], spheres.center(3)[1], spheres.center(3)[2]},
                       double(spheres.r[3]),
                       0.3};
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(cat("isa ", isa_name(isa)));
    ConeBatch want = batch_of(spheres, cases), got = want;
    std::fill(want.choice.begin(), want.choice.begin() + std::ptrdiff_t(cases.size()), 0.3);
    sample_cones(isa, want);
    std::array<std::vector<float>, 3> wi_float;
    for (int k = 0; k < 3; ++k) {
      wi_float[k].assign(got.radius.size(), -1.0f);
      got.wi_float[k] = wi_float[k].data();
      std::fill(got.center[k].begin(), got.center[k].end(), 1e300);  // not to be read
    }
    std::fill(got.radius.begin(), got.radius.end(), 1e300);  // nor these
    std::fill(got.choice.begin(), got.choice.end(), 1e300);
    sample_cones(isa, got, &one);
    int failures = 0, valid = 0;
    for (std::size_t i = 0; i < got.radius.size() && failures < 10; ++i) {
      const bool row = i < cases.size();
      const bool ok = row && want.pdf[i] > 0;
      valid += ok;
      for (int k = 0; k < 3; ++k) {
        // A padding row is left alone or gets 0 (the kernel's last lanes), never a direction.
        const float w = ok ? float(want.wi[k][i]) : 0.0f, got_k = wi_float[k][i];
        const bool right = same_bits(got_k, w) || (!row && got_k == -1.0f);
        failures += !right;
        EXPECT_TRUE(right) << "row " << i << " component " << k << ": " << got_k;
      }
      if (!row) continue;
      bool same =
          same_bits(got.wi[0][i], want.wi[0][i]) && same_bits(got.wi[1][i], want.wi[1][i]) &&
          same_bits(got.wi[2][i], want.wi[2][i]) && same_bits(got.dist[i], want.dist[i]) &&
          same_bits(got.pdf[i], want.pdf[i]) && same_bits(got.solid_angle[i], want.solid_angle[i]);
      failures += !same;
      EXPECT_TRUE(same) << "row " << i;
    }
    EXPECT_GT(valid, 3000);
  }
}

// sample_many's rows against sample() one by one, at every instruction set: the same light,
// radiance, direction, distance and density, bit for bit, and the float direction
// (ConeBatch::wi_float) rounded from it where the sample is valid, 0 where not; counts the
// kinds picked.
void expect_sample_many_is_sample(const LightSampler& lights, LightQueries& q, int* kinds_seen) {
  std::array<std::vector<float>, 3> wi_float;
  for (int k = 0; k < 3; ++k) {
    wi_float[k].assign(q.cones.radius.size(), -1.0f);
    q.cones.wi_float[k] = wi_float[k].data();
  }
  // The columns go with this function, also when an ASSERT returns early.
  struct Unpoint {
    ConeBatch& cones;
    ~Unpoint() { cones.wi_float = {}; }
  } unpoint{q.cones};
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(cat("isa ", isa_name(isa)));
    lights.sample_many(isa, q);
    for (std::size_t i = 0; i < q.size(); ++i) {
      for (int k = 0; k < 3; ++k)
        ASSERT_TRUE(same_bits(wi_float[k][i], q.valid(i) ? float(q.wi(i)[k]) : 0.0f))
            << "query " << i;
      LightSample want = lights.sample(q.ref(i), q.u_light[i], q.u_part[i], q.cones.u1[i],
                                       q.cones.u2[i], q.time_of(i));
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
}

// Query i: the shading point and random numbers.
void set_query(LightQueries& q, std::size_t i, const glm::dvec3& ref, Rng& rng) {
  for (int k = 0; k < 3; ++k)
    q.cones.ref[k][i] = ref[k];
  q.cones.u1[i] = rng.uniform(), q.cones.u2[i] = rng.uniform();
  q.u_light[i] = rng.uniform(), q.u_part[i] = rng.uniform();
}

// n queries from points in the cube [-4, 4]³, one in twenty inside the sphere light of radius
// 0.5 at (0, 3, 0) that the scenes below have (sampled by area there).
void set_queries_around(LightQueries& q, std::size_t n, uint64_t seed) {
  Rng rng(seed);
  q.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    glm::dvec3 ref = i % 20 == 0 ? glm::dvec3(0, 3, 0.1 * rng.uniform())
                                 : glm::dvec3(8 * rng.uniform() - 4, 8 * rng.uniform() - 4,
                                              8 * rng.uniform() - 4);
    set_query(q, i, ref, rng);
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
  LightQueries q;
  set_queries_around(q, 4000, 3);
  int kinds_seen[8] = {};
  expect_sample_many_is_sample(lights, q, kinds_seen);
  for (int k = 0; k < 3; ++k)
    EXPECT_GT(kinds_seen[k], 0) << "no query picked a light of kind " << k;
}

// The scene's one light a sphere (LightSampler's broadcast path), seen from outside and from
// inside (by area).
TEST(LightLanes, SampleManyIsSampleForOneSphereLight) {
  auto parsed = parse_scene(
      "camera 0 0 0 1\nlight 5 5 5\nsphere 0 3 0 0.5\nbrdf 0.5 0.5 0.5 0 0 0 1\n"
      "box -4 -4 -4 8 0.1 8\n",
      "one.scn");
  ASSERT_TRUE(parsed.ok());
  LightSampler lights(parsed.scene);
  LightQueries q;
  set_queries_around(q, 3001, 13);
  int kinds_seen[8] = {};
  expect_sample_many_is_sample(lights, q, kinds_seen);
  EXPECT_EQ(kinds_seen[std::size_t(tag_of<Sphere>)], int(q.size() * supported_isas().size()));
}

// Moving sphere lights (one textured) next to a still sphere and a box, each row at its own
// time (the path's): the kernel's cone about the centre at that time and, for rows inside the
// sphere then, area sampling, as sample() at that time does. Every row is at a different time,
// so a row given another row's time, or the middle of the shutter, differs.
TEST(LightLanes, SampleManyIsSampleAtEachRowsTimeForMovingLights) {
  auto parsed = parse_scene(
      "camera 0 0 0 1\nlight 5 5 5\nmbsphere -2 3 0 2 3 0 0.5\nlight 1 2 3\n"
      "box 2 2 2 1 0.5 0.25\nlight 2 2 2\nsphere 0 -3 0 0.4\nlight 3 3 3\ntexture \"" +
          testing::source_path("scenes/checker.png") + "\"\nmbsphere 0 0 -3 0 1 3 0.7\n",
      "moving.scn");
  ASSERT_TRUE(parsed.ok()) << parsed.diagnostics.items.front().message;
  LightSampler lights(parsed.scene);
  Rng rng(5);
  LightQueries q;
  q.resize(4000);
  q.time.resize(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    q.time[i] = rng.uniform();
    // One row in ten at the first moving sphere's centre at its time (inside it, by area).
    glm::dvec3 ref = i % 10 == 0 ? glm::dvec3(-2 + 4 * q.time[i], 3, 0.1 * rng.uniform())
                                 : glm::dvec3(8 * rng.uniform() - 4, 8 * rng.uniform() - 4,
                                              8 * rng.uniform() - 4);
    set_query(q, i, ref, rng);
  }
  int kinds_seen[8] = {};
  expect_sample_many_is_sample(lights, q, kinds_seen);
  EXPECT_GT(kinds_seen[std::size_t(tag_of<MovingSphere>)], 0);
  EXPECT_GT(kinds_seen[std::size_t(tag_of<Sphere>)], 0);
  // The rows' samples depend on their times: the same queries at mid-shutter differ.
  std::vector<double> pdf_at_times(q.cones.pdf.begin(), q.cones.pdf.begin() + q.size());
  q.time.clear();
  lights.sample_many(supported_isas().front(), q);
  int moved = 0;
  for (std::size_t i = 0; i < q.size(); ++i)
    moved += q.light[i].tag() == tag_of<MovingSphere> && q.cones.pdf[i] != pdf_at_times[i];
  EXPECT_GT(moved, 100);
}

// The render computes only the numbers numbers_read() names (render/wavefront/lane_vertices.cpp):
// the others must change nothing sample() returns, and the count must be what each scene needs.
TEST(LightLanes, NumbersReadAreAllSamplingReads) {
  const char* kScenes[][2] = {
      {"light 1 1 1\nsphere 0 3 0 0.5\n", "2"},
      {"light 1 1 1\nsphere 0 3 0 0.5\nsphere 2 3 0 0.25\n", "3"},
      {"light 1 1 1\nsphere 0 3 0 0.5\nbox 2 2 2 1 0.5 0.25\n", "4"},
      {"light 1 1 1\nbox 2 2 2 1 0.5 0.25\n", "4"},
      {"light 1 1 1\nsphere 0 3 0 0.5\nmbsphere 2 3 0 2 4 1 0.25\n", "3"},
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
      LightSample a = lights.sample(ref, u[2], u[3], u[0], u[1], 0.5);
      for (int c = read; c < 4; ++c)
        u[c] = rng.uniform();  // what an unread number holds does not matter
      LightSample b = lights.sample(ref, u[2], u[3], u[0], u[1], 0.5);
      ASSERT_EQ(a.light, b.light) << "sample " << i;
      ASSERT_TRUE(same_bits(a.wi, b.wi) && same_bits(a.pdf, b.pdf)) << "sample " << i;
    }
  }
}

}  // namespace
}  // namespace raylane
