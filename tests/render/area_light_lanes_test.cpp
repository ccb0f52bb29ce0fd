// Area lights among several lights in float lanes (LightSampler::sample_many's area kernel,
// render/lights/light_lanes.h): every row that picks a triangle, a box or a cylinder is the scalar
// float instance of prims/triangle_light.h's, prims/box_faces.h's or prims/cylinder_light.h's steps
// bit for bit, at every instruction set this CPU has, a sphere's cone left as it was; the
// triangle's and the cylinder's float steps are unbiased light samplers (the box's are
// box_light_lanes_test's); and the light picked is std::upper_bound's over the choice
// probabilities, at their boundaries too (the guide table).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "raylane/core/strings.h"
#include "raylane/prims/area_light_sample.h"
#include "raylane/prims/box_faces.h"
#include "raylane/prims/cylinder_light.h"
#include "raylane/prims/triangle_light.h"
#include "raylane/render/lights/light_lanes.h"
#include "raylane/render/lights/lights.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sampling.h"
#include "raylane/render/samplers/sobol.h"
#include "raylane/scene/parser.h"
#include "support/light_checks.h"
#include "support/paths.h"
#include "support/same_bits.h"

namespace raylane {
namespace {

using testing::same_bits;

// A sphere, two boxes, a mesh of three triangles (one light each) and a cylinder, of unequal
// powers; the triangles are tri.obj placed at (0, 0, 2).
Scene several_lights_scene() {
  const std::string dir = testing::temp_dir();
  std::ofstream(dir + "/tri.obj") << "v 0 0 0\nv 1 0 0\nv 0.2 1 0\nv 1 1 0.5\nv -1 0.5 0.3\n"
                                     "f 1 2 3\nf 2 4 3\nf 1 3 5\n";
  auto parsed = parse_scene(
      "camera 0 0 0 1\n"
      "light 4 4 4\nsphere 3 0 1 0.5\n"
      "light 1 2 3\nbox -0.5 -0.4 1 1.2 0.8 0.6\nbox 2 2 -1 0.3 0.3 0.3\n"
      "light 6 5 4\nmesh tri.obj 0 0 2 1\n"
      "light 2 2 2\ncylinder -2 0 0 0 0 1 0.3\n"
      "brdf 0.5 0.5 0.5 0 0 0 1\nsphere 0 -3 0 0.5\n",
      dir + "/s.scn");
  EXPECT_TRUE(parsed.ok());
  return std::move(parsed.scene);
}

// The scalar float steps for one row on triangle `row`, and on box `row`.
AreaLightSample<float, glm::vec3> triangle_steps(const TriangleTable& t, uint32_t row,
                                                 const glm::vec3& ref, float u1, float u2,
                                                 float choice) {
  const TriangleLightPoint<float, glm::vec3> x =
      triangle_light_point<float>(t.p0(row), t.p1(row), t.p2(row), u1, u2);
  return area_light_sample<true>(ref, x.p, x.n, x.area, choice);
}
AreaLightSample<float, glm::vec3> box_steps(const BoxTable& boxes, uint32_t row,
                                            const glm::vec3& ref, float u_part, float u1, float u2,
                                            float choice) {
  const BoxFacePoint<float, glm::vec3> f =
      box_face_point<float>(boxes.lo(row), boxes.hi(row), ref, u_part, u1, u2);
  return area_light_sample<false>(ref, f.p, f.n, f.area, choice);
}

// The lanes' cylinder: the stored unit axis times the height, in float, as the kernel forms it.
AreaLightSample<float, glm::vec3> cylinder_steps(const CylinderTable& c, uint32_t row,
                                                 const glm::vec3& ref, float u_part, float u1,
                                                 float u2, float choice) {
  const glm::vec3 axis = c.unit_axis(row) * c.h[row];
  const CylinderLightPoint<float, glm::vec3> x =
      cylinder_light_point<float>(c.base(row), axis, c.r[row], ref, u_part, u1, u2);
  return area_light_sample<false>(ref, x.p, x.n, x.area, choice);
}

// Queries about the lights, from points around them and a few inside the first box.
LightQueries random_queries(std::size_t n, Rng& rng) {
  LightQueries q;
  q.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 ref =
        i % 10 == 0
            ? glm::dvec3(-0.5 + 1.2 * rng.uniform(), -0.4 + 0.8 * rng.uniform(), 1.3)
            : glm::dvec3(8 * rng.uniform() - 4, 8 * rng.uniform() - 4, 8 * rng.uniform() - 3);
    for (int k = 0; k < 3; ++k)
      q.cones.ref[k][i] = float(ref[k]);
    q.cones.u1[i] = unit_float(rng.uniform()), q.cones.u2[i] = unit_float(rng.uniform());
    q.u_light[i] = rng.uniform(), q.u_part[i] = rng.uniform();
  }
  return q;
}

TEST(AreaLightLanes, SampleManyIsTheScalarFloatStepsForEveryTriangleBoxAndCylinder) {
  const Scene scene = several_lights_scene();
  const LightSampler lights(scene);
  ASSERT_EQ(scene.lights.size(), 7u);
  Rng rng(29);
  const std::size_t n = 4001;  // a partial last batch at every width
  LightQueries q = random_queries(n, rng);
  std::array<std::vector<float>, 3> wi_float;
  for (std::size_t k = 0; k < 3; ++k) {
    wi_float[k].resize(q.cones.pdf.size());
    q.cones.wi_float[k] = wi_float[k].data();
  }
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(cat("isa ", isa_name(isa)));
    testing::fill_light_sentinels(q, &wi_float);
    lights.sample_many(isa, q);
    std::size_t by_kind[4] = {};  // triangle, box, cylinder, sphere rows
    for (std::size_t i = 0; i < n; ++i) {
      const glm::vec3 ref(q.cones.ref[0][i], q.cones.ref[1][i], q.cones.ref[2][i]);
      const PrimRef l = q.light_of(i);
      // The row's light is the one sample() picks with its number.
      const LightSample one = lights.sample(glm::dvec3(ref), q.u_light[i], q.u_part[i],
                                            q.cones.u1[i], q.cones.u2[i], 0.5);
      ASSERT_EQ(l, one.light) << "query " << i;
      const float choice = float(*lights.choice_of(l));
      AreaLightSample<float, glm::vec3> want{};
      if (l.tag() == tag_of<Triangle>) {
        ++by_kind[0];
        want = triangle_steps(scene.table<Triangle>(), l.row(), ref, q.cones.u1[i], q.cones.u2[i],
                              choice);
      } else if (l.tag() == tag_of<Box>) {
        ++by_kind[1];
        want = box_steps(scene.table<Box>(), l.row(), ref, float(q.u_part[i]), q.cones.u1[i],
                         q.cones.u2[i], choice);
      } else if (l.tag() == tag_of<Cylinder>) {
        ++by_kind[2];
        want = cylinder_steps(scene.table<Cylinder>(), l.row(), ref, float(q.u_part[i]),
                              q.cones.u1[i], q.cones.u2[i], choice);
      } else {  // a sphere's cone: light_lanes_test's
        ++by_kind[3];
        continue;
      }
      ASSERT_TRUE(same_bits(q.cones.pdf[i], want.pdf)) << "query " << i;
      for (std::size_t k = 0; k < 3; ++k)  // ConeBatch::wi_float: wi where valid, else 0
        ASSERT_TRUE(same_bits(wi_float[k][i], want.pdf > 0 ? q.cones.wi[k][i] : 0.0f))
            << "query " << i;
      if (!(want.pdf > 0)) continue;
      EXPECT_TRUE(same_bits(q.cones.wi[0][i], want.wi.x) &&
                  same_bits(q.cones.wi[1][i], want.wi.y) &&
                  same_bits(q.cones.wi[2][i], want.wi.z) && same_bits(q.cones.dist[i], want.dist))
          << "query " << i;
      const Material& m = scene.materials[scene.material_of(l)];
      EXPECT_EQ(testing::light_radiance(q, i), glm::vec3(m.emission));
    }
    for (std::size_t count : by_kind)
      EXPECT_GT(count, n / 50);
  }
}

// What the triangle shows from points on both sides (a triangle light emits from both), and
// close to it, by its float steps' samples and by directions cast at it
// (testing::expect_samples_estimate_what_the_light_shows).
TEST(AreaLightLanes, TriangleFloatStepsEstimateWhatTheTriangleShows) {
  TriangleTable t;
  t.append({glm::vec3(-0.5f, -0.4f, 1), glm::vec3(0.9f, -0.2f, 1.3f), glm::vec3(0.1f, 0.8f, 0.9f)},
           {glm::vec3(0), glm::vec3(0), glm::vec3(0)}, 0);
  const glm::dvec3 normal = normalize(glm::dvec3(0.2, 0.1, 1));
  Rng rng(37);
  for (const glm::dvec3 ref : {glm::dvec3(0.1, 0, 0), glm::dvec3(1.5, 0, 0.2),
                               glm::dvec3(-0.3, 0.4, 2.5), glm::dvec3(0.1, 0.1, 1.05)}) {
    SCOPED_TRACE(cat("from (", ref.x, ", ", ref.y, ", ", ref.z, ")"));
    const glm::vec3 from(ref);
    testing::expect_samples_estimate_what_the_light_shows(
        glm::dvec3(from), normal, rng,
        [&](float, float u1, float u2) { return triangle_steps(t, 0, from, u1, u2, 1.0f); },
        [&](const Rayd& ray) { return std::isfinite(intersect_ref(t, 0, ray)); }, 0.02);
  }
}

// The cylinder's, from points that see its side alone, from close by, its side and top cap,
// and its base cap alone (one-sided: its outside emits).
TEST(AreaLightLanes, CylinderFloatStepsEstimateWhatTheCylinderShows) {
  CylinderTable c;
  ASSERT_FALSE(c.append(std::array<double, 7>{0.5, 0.2, 1, -0.6, 0.3, 0.9, 0.3}, 0));
  const glm::dvec3 normal = normalize(glm::dvec3(0.2, 0.1, 1));
  const glm::dvec3 across = normalize(glm::dvec3(0.3, 0.6, 0));  // across the axis
  Rng rng(43);
  for (const glm::dvec3 ref :
       {glm::dvec3(0.5, 0.95, 1.45), glm::dvec3(0.2, 0.35, 1.45) + 0.32 * across,
        glm::dvec3(-0.067, 1.234, 2.301), glm::dvec3(0.52, 0.19, 0.97)}) {
    SCOPED_TRACE(cat("from (", ref.x, ", ", ref.y, ", ", ref.z, ")"));
    const glm::vec3 from(ref);
    testing::expect_samples_estimate_what_the_light_shows(
        glm::dvec3(from), normal, rng,
        [&](float u_part, float u1, float u2) {
          return cylinder_steps(c, 0, from, u_part, u1, u2, 1.0f);
        },
        [&](const Rayd& ray) {
          const double t = intersect_ref(c, 0, ray);
          return std::isfinite(t) && dot(ray.d, surface_ref(c, 0, ray, t).ng) < 0;
        },
        0.02);
  }
}

// A mesh light of `count` triangles whose areas fall by a factor of 4^shrink from one to the
// next. Unequal (shrink 1, powers from 1 to 4^-(count-1)): most of the guide table's entries
// point at the first few lights, and the last ones share an entry. Equal (shrink 0): the
// cumulative choices fall on the entries' bounds, where a number just below one may round up
// onto the next entry when the table's index is computed (for 13 lights, three do).
Scene fan_of_lights_scene(int count, int shrink) {
  const std::string dir = testing::temp_dir();
  std::string obj;
  for (int t = 0; t < count; ++t) {
    const double s = std::ldexp(1.0, -t * shrink), z = 0.5 * t;  // exact in float
    obj += cat("v 0 0 ", z, "\nv ", s, " 0 ", z, "\nv 0 ", s, " ", z, "\n");
    obj += cat("f ", 3 * t + 1, " ", 3 * t + 2, " ", 3 * t + 3, "\n");
  }
  std::ofstream(dir + "/fan.obj") << obj;
  auto parsed = parse_scene("camera 0 0 0 1\nlight 1 1 1\nmesh fan.obj 0 0 2 1\n", dir + "/s.scn");
  EXPECT_TRUE(parsed.ok());
  return std::move(parsed.scene);
}

// The light a number picks is the first whose cumulative choice exceeds it (the last if none
// does), as std::upper_bound finds it: at each boundary, just below and above it, at the guide
// table's entries' bounds and next to them, and at random; for lights of near powers and of
// very unequal ones.
void expect_pick_is_upper_bound(const Scene& scene, std::size_t count) {
  const LightSampler lights(scene);
  ASSERT_EQ(scene.lights.size(), count);
  std::vector<double> cdf;
  double acc = 0;
  for (PrimRef l : scene.lights)
    cdf.push_back(acc += *lights.choice_of(l));
  cdf.back() = 1.0;
  auto expected = [&](double u) {
    const std::size_t k = std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin();
    return scene.lights[std::min(k, cdf.size() - 1)];
  };
  std::vector<double> us = {0.0, std::nextafter(1.0, 0.0)};
  for (double c : cdf)
    us.insert(us.end(), {c, std::nextafter(c, 0.0), std::nextafter(c, 2.0)});
  for (std::size_t j = 0; j < count; ++j) {
    const double bound = double(j) / double(count);
    us.insert(us.end(), {bound, std::nextafter(bound, 0.0), std::nextafter(bound, 2.0)});
  }
  Rng rng(41);
  for (int i = 0; i < 10000; ++i)
    us.push_back(rng.uniform());
  const glm::dvec3 ref(0, -2, 0);
  for (double u : us)
    ASSERT_EQ(lights.sample(ref, u, 0.5, 0.5, 0.5, 0.5).light, expected(u)) << "u " << u;
}

TEST(AreaLightLanes, PickIsTheUpperBoundOfTheCumulativeChoices) {
  expect_pick_is_upper_bound(several_lights_scene(), 7);
  expect_pick_is_upper_bound(fan_of_lights_scene(20, 1), 20);
  expect_pick_is_upper_bound(fan_of_lights_scene(13, 0), 13);
  expect_pick_is_upper_bound(fan_of_lights_scene(25, 0), 25);
}

}  // namespace
}  // namespace raylane
