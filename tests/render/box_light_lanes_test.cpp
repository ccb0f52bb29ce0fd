// A scene's one box light sampled in float lanes (LightSampler::sample_many, render/lights/
// light_lanes.h): every row the scalar float instance of prims/box_faces.h's steps bit for bit
// at every instruction set this CPU has, and that float instance an unbiased light sampler: its
// estimate of the light's irradiance-like integral agrees with one by directions cast at the
// box, within 4 standard errors, from points that see one, two and three faces.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "raylane/core/strings.h"
#include "raylane/prims/area_light_sample.h"
#include "raylane/prims/box_faces.h"
#include "raylane/render/lights/light_lanes.h"
#include "raylane/render/lights/lights.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sampling.h"
#include "raylane/render/samplers/sobol.h"
#include "raylane/scene/parser.h"
#include "support/light_checks.h"
#include "support/same_bits.h"

namespace raylane {
namespace {

using testing::same_bits;

constexpr const char* kBoxLight = "box -0.5 -0.4 1 1.2 0.8 0.6";

Scene box_light_scene() {
  auto parsed = parse_scene(cat("camera 0 0 0 1\nlight 3 2 1\n", kBoxLight,
                                "\nbrdf 0.5 0.5 0.5 0 0 0 1\nsphere 0 -3 0 0.5\n"),
                            "box.scn");
  EXPECT_TRUE(parsed.ok());
  return std::move(parsed.scene);
}

// The scalar float steps for one row: the point on the faces seen and the sample it makes.
AreaLightSample<float, glm::vec3> float_steps(const BoxTable& boxes, uint32_t row,
                                              const glm::vec3& ref, float u_part, float u1,
                                              float u2, float choice) {
  const BoxFacePoint<float, glm::vec3> f =
      box_face_point<float>(boxes.lo(row), boxes.hi(row), ref, u_part, u1, u2);
  return area_light_sample<false>(ref, f.p, f.n, f.area, choice);
}

TEST(BoxLightLanes, SampleManyIsTheScalarFloatStepsForOneBoxLight) {
  const Scene scene = box_light_scene();
  const LightSampler lights(scene);
  ASSERT_EQ(scene.lights.size(), 1u);
  const uint32_t row = scene.lights[0].row();
  // The choice is 1: the only light, no environment.
  const float choice = 1.0f;
  LightQueries q;
  Rng rng(23);
  const std::size_t n = 3001;  // a partial last batch at every width
  q.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    // Around the box, one point in ten inside it (no face faces it: no sample).
    const bool inside = i % 10 == 0;
    const glm::dvec3 ref =
        inside ? glm::dvec3(-0.5 + 1.2 * rng.uniform(), -0.4 + 0.8 * rng.uniform(),
                            1 + 0.6 * rng.uniform())
               : glm::dvec3(6 * rng.uniform() - 3, 6 * rng.uniform() - 3, 6 * rng.uniform() - 2);
    for (int k = 0; k < 3; ++k)
      q.cones.ref[k][i] = float(ref[k]);
    q.cones.u1[i] = unit_float(rng.uniform()), q.cones.u2[i] = unit_float(rng.uniform());
    q.u_light[i] = rng.uniform(), q.u_part[i] = rng.uniform();
  }
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(cat("isa ", isa_name(isa)));
    lights.sample_many(isa, q);
    std::size_t inside_count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const glm::vec3 ref(q.cones.ref[0][i], q.cones.ref[1][i], q.cones.ref[2][i]);
      const auto want = float_steps(scene.table<Box>(), row, ref, float(q.u_part[i]), q.cones.u1[i],
                                    q.cones.u2[i], choice);
      ASSERT_EQ(q.light_of(i), scene.lights[0]) << "query " << i;
      ASSERT_TRUE(same_bits(q.cones.pdf[i], want.pdf)) << "query " << i;
      EXPECT_EQ(testing::light_radiance(q, i), glm::vec3(3, 2, 1));
      // Every point outside the box sees a face, so its sample is valid; none inside is.
      const glm::vec3 lo = scene.table<Box>().lo(row), hi = scene.table<Box>().hi(row);
      bool inside = true;
      for (int k = 0; k < 3; ++k)
        inside = inside && ref[k] > lo[k] && ref[k] < hi[k];
      inside_count += inside;
      ASSERT_EQ(want.pdf > 0, !inside) << "query " << i;
      if (inside) continue;
      EXPECT_TRUE(same_bits(q.cones.wi[0][i], want.wi.x) &&
                  same_bits(q.cones.wi[1][i], want.wi.y) &&
                  same_bits(q.cones.wi[2][i], want.wi.z) && same_bits(q.cones.dist[i], want.dist))
          << "query " << i;
    }
    EXPECT_GE(inside_count, (n + 9) / 10);
  }
}

// What the box shows from points that see one, two and three faces, and close to a face (where
// cos / pdf varies most over it), by its float steps' samples and by directions cast at it
// (testing::expect_samples_estimate_what_the_light_shows).
TEST(BoxLightLanes, FloatStepsEstimateWhatTheBoxShows) {
  const Scene scene = box_light_scene();
  const BoxTable& boxes = scene.table<Box>();
  const uint32_t row = scene.lights[0].row();
  const glm::dvec3 normal = normalize(glm::dvec3(0.2, 0.1, 1));
  Rng rng(31);
  for (const glm::dvec3 ref : {glm::dvec3(0.1, 0, 0), glm::dvec3(1.5, 0, 0.2),
                               glm::dvec3(-2, 1.5, 3), glm::dvec3(0.1, 0.1, 0.95)}) {
    SCOPED_TRACE(cat("from (", ref.x, ", ", ref.y, ", ", ref.z, ")"));
    const glm::vec3 from(ref);
    testing::expect_samples_estimate_what_the_light_shows(
        glm::dvec3(from), normal, rng,
        [&](float u_part, float u1, float u2) {
          return float_steps(boxes, row, from, u_part, u1, u2, 1.0f);
        },
        [&](const Rayd& ray) {  // a front face hit: a box emits from its outside
          const double t = intersect_ref(boxes, row, ray);
          return std::isfinite(t) && dot(ray.d, surface_ref(boxes, row, ray, t).ng) < 0;
        },
        0.05);
  }
}

}  // namespace
}  // namespace raylane
