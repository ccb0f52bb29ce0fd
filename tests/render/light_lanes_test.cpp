// Sphere lights' cones in float lanes (render/lights/light_lanes.h) against the scalar float
// instance of the steps they run (prims/sphere_cone.h), bit for bit at every instruction set this
// CPU has; that float instance against the double one (Sphere::sample_subtended) within float's
// error bound; and LightSampler::sample_many against sample() on a scene with every kind of light.
#include "raylane/render/lights/light_lanes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "env_maps.h"
#include "raylane/core/strings.h"
#include "raylane/core/warps.h"
#include "raylane/image/pfm.h"
#include "raylane/prims/sphere_cone.h"
#include "raylane/render/lights/lights.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sobol.h"
#include "raylane/scene/parser.h"
#include "support/light_checks.h"
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

// The cases as the render's float columns hold them: points and numbers rounded (the numbers
// below 1, unit_float), the spheres' own float centres and radii.
ConeBatch batch_of(const SphereTable& spheres, const std::vector<Case>& cases) {
  ConeBatch b;
  b.resize(cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    for (int k = 0; k < 3; ++k)
      b.ref[k][i] = float(c.ref[k]), b.center[k][i] = spheres.center(c.sphere)[k];
    b.radius[i] = spheres.r[c.sphere], b.u1[i] = unit_float(c.u1), b.u2[i] = unit_float(c.u2);
    b.choice[i] = i % 2 == 0 ? 1.0f : 0.3f;  // a light among others: pdf is a true division
  }
  return b;
}

glm::vec3 row3(const std::array<std::vector<float>, 3>& c, std::size_t i) {
  return {c[0][i], c[1][i], c[2][i]};
}

// The cone of batch row i by the steps' instance at N (float: the lanes' reference; double: the
// reference, at the same inputs widened).
template <class N, class V3>
SphereCone<N, V3> steps_for_row(const ConeBatch& b, std::size_t i) {
  return sphere_cone<N>(V3(row3(b.center, i)), N(b.radius[i]), V3(row3(b.ref, i)), N(b.u1[i]),
                        N(b.u2[i]));
}

TEST(LightLanes, ConesAreTheScalarFloatSteps) {
  SphereTable spheres;
  std::vector<Case> cases = random_cases(spheres, 20000, 7);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(cat("isa ", isa_name(isa)));
    ConeBatch b = batch_of(spheres, cases);
    sample_cones(isa, b);
    int outside = 0, failures = 0;
    for (std::size_t i = 0; i < cases.size() && failures < 10; ++i) {
      const SphereCone<float, glm::vec3> s = steps_for_row<float, glm::vec3>(b, i);
      const float pdf = s.solid_angle > 0 ? b.choice[i] / s.solid_angle : 0.0f;
      outside += s.solid_angle > 0;
      const bool ok = same_bits(b.solid_angle[i], s.solid_angle) && same_bits(b.pdf[i], pdf) &&
                      (!(s.solid_angle > 0) ||
                       (same_bits(row3(b.wi, i), s.wi) && same_bits(b.dist[i], s.dist)));
      failures += !ok;
      EXPECT_TRUE(ok) << "row " << i << ": lanes wi " << b.wi[0][i] << " " << b.wi[1][i] << " "
                      << b.wi[2][i] << " dist " << b.dist[i] << " solid " << b.solid_angle[i]
                      << "; scalar wi " << s.wi.x << " " << s.wi.y << " " << s.wi.z << " dist "
                      << s.dist << " solid " << s.solid_angle;
    }
    // Most rows sample the cone; a tenth are inside, and those within float's resolution of
    // their sphere (about a quarter are 1e-9 to 1e-6 radii away) count as inside in float.
    EXPECT_GT(outside, 13000);
  }
}

// Float's error bound for the cone of a sphere of radius r seen from distance d (u = 2^-24),
// from the steps' roundings (prims/sphere_cone.h): each of the dozen steps to the cone's
// 1 − cos θmax rounds once, 12u relative, except √(1 − sin²θmax), whose argument x carries an
// absolute 12u that the root turns into min(6u/√x, √(12u)); the solid angle carries both. The
// sampled direction's angle inherits that relative error of 1 − cos θ (a half of it, through
// sin θ) plus a dozen roundings of the frame and the turn. The distance d·cos θ − √y, y = r² −
// d²sin²θ, is a difference of terms of size d (a dozen roundings of d, and the direction's error
// across the sphere), and y's absolute error δy = (8u + the cone's relative error)·r² becomes
// min(δy/(2√y), √δy) in the root: large where the sampled direction grazes the sphere.
struct ConeBound {
  double solid_angle, wi, dist;
};

ConeBound cone_bound(const SphereCone<double, glm::dvec3>& exact, double r, const glm::dvec3& w) {
  const double u = 0x1p-24, d = length(w), sin2_max = r * r / (d * d);
  const double x = std::max(0.0, 1 - sin2_max);
  const double omc = 12 * u + std::min(6 * u / std::sqrt(x), std::sqrt(12 * u));
  // The direction: the angle's relative error times the cone's half-angle (sin θmax bounds it).
  const double wi = 16 * u + omc * std::sqrt(sin2_max);
  const double root_y = std::max(0.0, dot(exact.wi, w) - exact.dist);  // √y
  const double dy = (8 * u + omc) * r * r;
  const double root = root_y > 0 ? std::min(dy / (2 * root_y), std::sqrt(dy)) : std::sqrt(dy);
  return {omc * exact.solid_angle, wi, (16 * u + 2 * wi) * d + root};
}

// The float steps against the double ones at the same inputs, within cone_bound; a planted
// error of one part in 10^5 in the float's solid angle, direction or distance is caught.
TEST(LightLanes, FloatConesAreWithinTheirBoundOfTheDoubleOnes) {
  SphereTable spheres;
  std::vector<Case> cases = random_cases(spheres, 20000, 7);
  const ConeBatch b = batch_of(spheres, cases);
  int outside = 0, beyond = 0, planted_beyond = 0, planted_wi = 0, planted_dist = 0, disagree = 0;
  double worst[3] = {};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto f = steps_for_row<float, glm::vec3>(b, i);
    const auto d = steps_for_row<double, glm::dvec3>(b, i);
    const glm::dvec3 w = glm::dvec3(row3(b.center, i)) - glm::dvec3(row3(b.ref, i));
    if ((f.solid_angle > 0) != (d.solid_angle > 0)) {
      // Inside in one precision, outside in the other: only within float's resolution of the
      // surface (d² and r² each a few roundings from exact).
      ++disagree;
      ASSERT_LE(std::abs(length(w) - double(b.radius[i])), 8 * 0x1p-24 * length(w)) << "row " << i;
      continue;
    }
    if (!(d.solid_angle > 0)) continue;
    ++outside;
    const ConeBound bound = cone_bound(d, b.radius[i], w);
    const double e[3] = {std::abs(f.solid_angle - d.solid_angle) / bound.solid_angle,
                         length(glm::dvec3(f.wi) - d.wi) / bound.wi,
                         std::abs(f.dist - d.dist) / bound.dist};
    for (int k = 0; k < 3; ++k)
      worst[k] = std::max(worst[k], e[k]);
    beyond += e[0] > 1 || e[1] > 1 || e[2] > 1;
    // Planted: one part in 10^5 off the solid angle, the direction, and the distance (of the
    // distance to the centre, the scale its bound is in).
    planted_beyond += std::abs(f.solid_angle * (1 + 1e-5) - d.solid_angle) > bound.solid_angle;
    planted_wi += length(glm::dvec3(f.wi) + glm::dvec3(1e-5, 0, 0) - d.wi) > bound.wi;
    planted_dist += std::abs(f.dist + 1e-5 * length(w) - d.dist) > bound.dist;
  }
  EXPECT_EQ(beyond, 0);
  EXPECT_GT(planted_beyond, outside / 2);
  EXPECT_GT(planted_wi, outside / 2);
  // The distance's bound is wide near the sphere and where the sample grazes it (its √ terms):
  // there 10^-5 of d passes, and about 40 % of the rows are caught.
  EXPECT_GT(planted_dist, outside / 3);
  std::printf("planted errors beyond the bound: solid angle %d, direction %d, distance %d of %d\n",
              planted_beyond, planted_wi, planted_dist, outside);
  EXPECT_GT(outside, 13000);
  std::printf(
      "largest error / bound: solid angle %.3g, direction %.3g, distance %.3g; %d rows "
      "inside in one precision only\n",
      worst[0], worst[1], worst[2], disagree);
}

// Every row about one sphere (ConeSphere) gives the answers of the same sphere in the columns,
// bit for bit, and the float directions (ConeBatch::wi_float) are wi rounded where pdf > 0 and
// 0 elsewhere; padding rows never get a direction.
TEST(LightLanes, ConesAboutOneSphereAreTheColumnsAnswers) {
  SphereTable spheres;
  std::vector<Case> cases = random_cases(spheres, 4001, 9);
  for (Case& c : cases)
    c.sphere = 3;  // the refs stay where they were: some inside sphere 3, most far outside
  const ConeSphere one{
      {spheres.center(3)[0], spheres.center(3)[1], spheres.center(3)[2]}, spheres.r[3], 0.3f};
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(cat("isa ", isa_name(isa)));
    ConeBatch want = batch_of(spheres, cases), got = want;
    std::fill(want.choice.begin(), want.choice.begin() + std::ptrdiff_t(cases.size()), 0.3);
    sample_cones(isa, want);
    std::array<std::vector<float>, 3> wi_float;
    for (int k = 0; k < 3; ++k) {
      wi_float[k].assign(got.radius.size(), -1.0f);
      got.wi_float[k] = wi_float[k].data();
      std::fill(got.center[k].begin(), got.center[k].end(), std::nanf(""));  // not to be read
    }
    std::fill(got.radius.begin(), got.radius.end(), std::nanf(""));  // nor these
    std::fill(got.choice.begin(), got.choice.end(), std::nanf(""));
    sample_cones(isa, got, &one);
    int failures = 0, valid = 0;
    for (std::size_t i = 0; i < got.radius.size() && failures < 10; ++i) {
      const bool row = i < cases.size();
      const bool ok = row && want.pdf[i] > 0;
      valid += ok;
      for (int k = 0; k < 3; ++k) {
        // A padding row is left alone or gets 0 (the kernel's last lanes), never a direction.
        const float w = ok ? want.wi[k][i] : 0.0f, got_k = wi_float[k][i];
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

// A sphere light's centre (a moving one's at `time`) and radius, as sample_many hands them to
// the float kernel, rounded; and the same centre in double.
struct LightSphere {
  glm::vec3 center;
  glm::dvec3 exact_center;
  float r;
};
LightSphere light_sphere(const Scene& scene, PrimRef light, double time) {
  if (light.tag() == tag_of<MovingSphere>) {
    const MovingSphereTable& t = scene.table<MovingSphere>();
    const glm::dvec3 c = t.center_at(light.row(), time);
    return {glm::vec3(c), c, t.r[light.row()]};
  }
  const SphereTable& t = scene.table<Sphere>();
  return {t.center(light.row()), glm::dvec3(t.center(light.row())), t.r[light.row()]};
}

// A cone row of sample_many (a sphere light seen from outside) against sample()'s double answer:
// the direction and distance within cone_bound of the double steps at the kernel's own inputs,
// the density within the solid angle's bound and two roundings (the choice's and the quotient).
void expect_cone_row_near(const Scene& scene, const LightQueries& q, std::size_t i,
                          const LightSample& want) {
  const LightSphere s = light_sphere(scene, want.light, q.time_of(i));
  const glm::dvec3 ref = q.ref(i), c(s.center);
  const auto exact =
      sphere_cone<double>(c, double(s.r), ref, double(q.cones.u1[i]), double(q.cones.u2[i]));
  ASSERT_GT(exact.solid_angle, 0) << "query " << i;
  const ConeBound bound = cone_bound(exact, s.r, c - ref);
  // The choice probability, from the double sample about the exact centre.
  const auto at_exact = sphere_cone<double>(s.exact_center, double(s.r), ref, double(q.cones.u1[i]),
                                            double(q.cones.u2[i]));
  const double choice = want.pdf * at_exact.solid_angle, pdf = choice / exact.solid_angle;
  const double pdf_bound = (bound.solid_angle / exact.solid_angle + 3 * 0x1p-24) * pdf;
  EXPECT_LE(length(q.wi(i) - exact.wi), bound.wi) << "query " << i;
  EXPECT_LE(std::abs(q.cones.dist[i] - exact.dist), bound.dist) << "query " << i;
  EXPECT_LE(std::abs(q.pdf(i) - pdf), pdf_bound) << "query " << i;
}

// sample_many's rows against sample() one by one, at every instruction set: the same light and
// validity; a sphere light's cone (the float kernel) within its error bound (expect_cone_row_near),
// an untextured triangle's, box's or cylinder's its radiance only (the area kernel's rows are
// area_light_lanes_test's), every other row sample()'s answer rounded to float, bit for bit,
// with its radiance; and the float direction (ConeBatch::wi_float) the row's where the sample is
// valid, 0 where not. Counts the kinds picked.
void expect_sample_many_is_sample(const Scene& scene, const LightSampler& lights, LightQueries& q,
                                  int* kinds_seen, bool with_cones = true) {
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
    testing::fill_light_sentinels(q, &wi_float);
    lights.sample_many(isa, q);
    int cones = 0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      for (int k = 0; k < 3; ++k)
        ASSERT_TRUE(same_bits(wi_float[k][i], q.valid(i) ? q.cones.wi[k][i] : 0.0f))
            << "query " << i;
      LightSample want = lights.sample(q.ref(i), q.u_light[i], q.u_part[i], q.cones.u1[i],
                                       q.cones.u2[i], q.time_of(i));
      ASSERT_EQ(q.light_of(i), want.light) << "query " << i;
      // An untextured triangle, box or cylinder: by the area kernel in float, whose rows
      // area_light_lanes_test holds to the float steps bit for bit (here only its light and
      // radiance: float and double may differ in validity within a rounding of an edge).
      const auto tag = want.light.tag();
      const bool area_kind =
          tag == tag_of<Triangle> || tag == tag_of<Box> || tag == tag_of<Cylinder>;
      const bool textured = scene.materials[scene.material_of(want.light)].texture >= 0;
      ++kinds_seen[std::size_t(q.light_of(i).tag())];
      if (area_kind && !textured) {
        EXPECT_EQ(testing::light_radiance(q, i), glm::vec3(want.le));
        continue;
      }
      ASSERT_EQ(q.valid(i), want.valid()) << "query " << i;
      if (!want.valid()) continue;
      const bool sphere =
          want.light.tag() == tag_of<Sphere> || want.light.tag() == tag_of<MovingSphere>;
      if (sphere && want.n == glm::dvec3(0, 0, 0)) {  // by its cone (area samples have a normal)
        ++cones;
        // An untextured sphere's radiance (for a scene's one light, LightQueries::one_light's);
        // a textured one's depends on the point, which the cone puts within its bound.
        if (!textured) {
          EXPECT_EQ(testing::light_radiance(q, i), glm::vec3(want.le)) << "query " << i;
        }
        expect_cone_row_near(scene, q, i, want);
        continue;
      }
      EXPECT_EQ(testing::light_radiance(q, i), glm::vec3(want.le));
      // The point is ref + wi·dist, so these pin it down too.
      EXPECT_TRUE(same_bits(q.cones.wi[0][i], float(want.wi.x)) &&
                  same_bits(q.cones.wi[1][i], float(want.wi.y)) &&
                  same_bits(q.cones.wi[2][i], float(want.wi.z)) &&
                  same_bits(q.cones.pdf[i], float(want.pdf)) &&
                  same_bits(q.cones.dist[i], float(want.dist)))
          << "query " << i;
    }
    EXPECT_EQ(cones > 0, with_cones);
  }
}

// Query i: the shading point and random numbers.
void set_query(LightQueries& q, std::size_t i, const glm::dvec3& ref, Rng& rng) {
  for (int k = 0; k < 3; ++k)
    q.cones.ref[k][i] = float(ref[k]);
  q.cones.u1[i] = unit_float(rng.uniform()), q.cones.u2[i] = unit_float(rng.uniform());
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
  expect_sample_many_is_sample(parsed.scene, lights, q, kinds_seen);
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
  expect_sample_many_is_sample(parsed.scene, lights, q, kinds_seen);
  EXPECT_EQ(kinds_seen[std::size_t(tag_of<Sphere>)], int(q.size() * supported_isas().size()));
}

// Under an environment: alone (LightSampler's path without picks or cones), and beside a
// sphere light (the rows that pick it sampled together among the cones' rows). Every row's
// sample is sample()'s, bit for bit.
TEST(LightLanes, SampleManyIsSampleUnderAnEnvironment) {
  const std::string map = testing::temp_dir() + "/sun.pfm";
  std::ofstream(map, std::ios::binary) << encode_pfm(testing::sun_map(50));
  for (bool with_sphere : {false, true}) {
    SCOPED_TRACE(with_sphere ? "with a sphere light" : "alone");
    auto parsed = parse_scene(
        "camera 0 0 0 1\nenvironment \"" + map + "\" 1\nbrdf 0.5 0.5 0.5 0 0 0 1\n" +
            (with_sphere ? "light 5 5 5\nsphere 0 3 0 0.5\n" : "") + "box -4 -4 -4 8 0.1 8\n",
        "sky.scn");
    ASSERT_TRUE(parsed.ok());
    LightSampler lights(parsed.scene);
    LightQueries q;
    set_queries_around(q, 2003, 17);
    int kinds_seen[8] = {};
    expect_sample_many_is_sample(parsed.scene, lights, q, kinds_seen, with_sphere);
    int valid = 0;
    for (std::size_t i = 0; i < q.size(); ++i)
      valid += q.valid(i);
    EXPECT_GT(valid, int(q.size()) / 2);
  }
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
  expect_sample_many_is_sample(parsed.scene, lights, q, kinds_seen);
  EXPECT_GT(kinds_seen[std::size_t(tag_of<MovingSphere>)], 0);
  EXPECT_GT(kinds_seen[std::size_t(tag_of<Sphere>)], 0);
  // The rows' samples depend on their times: the same queries at mid-shutter differ.
  std::vector<double> pdf_at_times(q.cones.pdf.begin(), q.cones.pdf.begin() + q.size());
  q.time.clear();
  lights.sample_many(supported_isas().front(), q);
  int moved = 0;
  for (std::size_t i = 0; i < q.size(); ++i)
    moved += q.light_of(i).tag() == tag_of<MovingSphere> && q.cones.pdf[i] != pdf_at_times[i];
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
