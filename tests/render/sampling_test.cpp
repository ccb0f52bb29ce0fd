// Chi-square tests of the direction samplers against their densities (docs/hard-cases.md M4): the
// cosine hemisphere, the course's BSDF lobes (Phong reflection at α = 1, 10, 1000, a mixture,
// transmission in and out of glass) and solid-angle sampling of sphere lights.
#include <gtest/gtest.h>

#include "chi2.h"
#include "raylane/render/lights/lights.h"
#include "raylane/render/materials/bsdf.h"
#include "raylane/render/samplers/sampling.h"
#include "raylane/scene/parser.h"

namespace raylane {
namespace {

using testing::Chi2Result;
using testing::Chi2Setup;

// Every chi-square run of this file shares one family-wise level of 1 % (Šidák).
constexpr int kChi2Runs = 14;
const double kLevel = testing::sidak_level(0.01, kChi2Runs);

void expect_fits(const Chi2Result& r) {
  EXPECT_FALSE(r.zero_cell_hit);
  EXPECT_GT(r.p_value, kLevel) << "chi2 = " << r.statistic << " with " << r.dof << " dof";
}

TEST(Sampling, CosineHemisphereFollowsItsPdf) {
  glm::dvec3 n = normalize(glm::dvec3(1, 2, 3));
  Frame f(n);
  Chi2Setup setup;
  setup.axis = glm::dvec3(0, 0, 1);  // bins not aligned with the lobe
  auto sample = [&](Rng& rng) -> std::optional<glm::dvec3> {
    double u1 = rng.uniform(), u2 = rng.uniform();
    return f.to_world(sample_cosine_hemisphere(u1, u2));
  };
  auto pdf = [&](const glm::dvec3& w) { return cosine_hemisphere_pdf(dot(w, n)); };
  expect_fits(testing::chi2_test(setup, sample, pdf, 1));
}

// The thin lens's disc: Malley's method read backwards — a uniform disc point lifted onto the
// hemisphere is cosine-distributed — so the cosine density's chi-square tests the disc.
TEST(Sampling, ConcentricDiscIsUniform) {
  Chi2Setup setup;
  setup.z_min = 0;
  auto sample = [](Rng& rng) -> std::optional<glm::dvec3> {
    glm::dvec3 p = sample_concentric_disc(rng.uniform(), rng.uniform());
    double r2 = p.x * p.x + p.y * p.y;
    if (!(r2 <= 1)) return std::nullopt;
    return glm::dvec3(p.x, p.y, std::sqrt(1 - r2));
  };
  auto pdf = [](const glm::dvec3& w) { return cosine_hemisphere_pdf(w.z); };
  expect_fits(testing::chi2_test(setup, sample, pdf, 14));
}

Material make_material(glm::vec3 kd, glm::vec3 ks, float alpha, glm::vec3 kt = {0, 0, 0},
                       float ior = 1) {
  Material m;
  m.kd = kd, m.ks = ks, m.alpha = alpha, m.kt = kt, m.ior = ior;
  return m;
}

// Chi-square of Bsdf::sample against Bsdf::pdf for one outgoing direction, binned around
// `axis` over the cap z ≥ z_min.
Chi2Result bsdf_chi2(const Material& m, const glm::dvec3& wo, const glm::dvec3& axis, double z_min,
                     uint64_t seed) {
  glm::dvec3 n(0, 0, 1);
  Bsdf bsdf(m, n, wo);
  Chi2Setup setup;
  setup.axis = axis;
  setup.z_min = z_min;
  auto sample = [&](Rng& rng) -> std::optional<glm::dvec3> {
    double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    BsdfSample s = bsdf.sample(u0, u1, u2);
    if (!s.valid()) return std::nullopt;
    return s.wi;
  };
  auto pdf = [&](const glm::dvec3& w) { return bsdf.pdf(w); };
  return testing::chi2_test(setup, sample, pdf, seed);
}

TEST(Sampling, PhongLobeFollowsItsPdf) {
  for (double alpha : {1.0, 10.0, 1000.0}) {
    for (glm::dvec3 wo :
         {normalize(glm::dvec3(0.3, 0.1, 1)), normalize(glm::dvec3(-1, 0.4, 0.5))}) {
      SCOPED_TRACE(::testing::Message() << "alpha " << alpha << " wo " << wo.x << "," << wo.z);
      Material m = make_material({0, 0, 0}, {1, 1, 1}, float(alpha));
      glm::dvec3 mirror(-wo.x, -wo.y, wo.z);
      // The lobe of wi lies within 1 − cos γ ≈ 60/(α+1) of the mirror direction up to e^-15.
      double z_min = std::max(-1.0, 1 - 60 / (alpha + 1));
      expect_fits(bsdf_chi2(m, wo, mirror, z_min, 10 + uint64_t(alpha)));
    }
  }
}

TEST(Sampling, DiffusePlusGlossyMixtureFollowsItsPdf) {
  Material m = make_material({0.5f, 0.4f, 0.3f}, {0.3f, 0.3f, 0.3f}, 10);
  expect_fits(bsdf_chi2(m, normalize(glm::dvec3(0.5, -0.2, 0.7)), glm::dvec3(0.2, 0.1, 1), -1, 3));
}

// Glass lobes: reflection and refraction, entering (wo outside) and leaving, where total
// internal reflection sends part of the refraction lobe back inside.
TEST(Sampling, TransmissionFollowsItsPdf) {
  Material m = make_material({0, 0, 0}, {0.04f, 0.04f, 0.04f}, 20, {1, 1, 1}, 1.5f);
  expect_fits(bsdf_chi2(m, normalize(glm::dvec3(0.6, 0, 0.8)), glm::dvec3(0.1, 0.2, 1), -1, 4));
  expect_fits(bsdf_chi2(m, normalize(glm::dvec3(0.5, 0.1, -0.6)), glm::dvec3(0.1, 0.2, 1), -1, 5));
}

// A sphere light seen from outside: uniform in its cone, binned in a frame tilted off the
// cone's axis; every sampled direction must hit the sphere at the returned point.
TEST(Sampling, SphereLightSolidAngleFollowsItsPdf) {
  auto parsed = parse_scene("camera 0 0 0 1\nlight 1 1 1\nsphere 0.3 0.2 2 0.8\n", "t.scn");
  ASSERT_TRUE(parsed.ok());
  const Scene& scene = parsed.scene;
  LightSampler lights(scene);
  for (glm::dvec3 ref :
       {glm::dvec3(0, 0, 0), glm::dvec3(0.3, 0.2, 0.9)}) {  // far, and 0.3 from the surface
    glm::dvec3 c(scene.table<Sphere>().center(0));          // the table's floats
    double r = scene.table<Sphere>().r[0];
    int off_sphere = 0;
    auto sample = [&](Rng& rng) -> std::optional<glm::dvec3> {
      double u[4] = {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
      LightSample s = lights.sample(ref, u[0], u[1], u[2], u[3], 0.5);
      if (!s.valid()) return std::nullopt;
      off_sphere += std::abs(length(s.p - c) - r) > 1e-9;
      return s.wi;
    };
    auto pdf = [&](const glm::dvec3& w) {
      glm::dvec3 to = c - ref;
      double d2 = length_squared(to), cos_max = std::sqrt(1 - r * r / d2);
      return dot(w, normalize(to)) >= cos_max ? 1 / (2 * kPi * (1 - cos_max)) : 0.0;
    };
    // Binned in the cone's own frame over exactly the cone: the density is discontinuous at
    // its edge, which no sub-sampling of a straddling cell integrates well; a sample outside
    // the cone falls in the "outside" cell, which expects 0 and fails the test.
    Chi2Setup setup;
    setup.axis = normalize(c - ref);
    setup.z_min = std::sqrt(1 - r * r / length_squared(c - ref));
    expect_fits(testing::chi2_test(setup, sample, pdf, 6));
    EXPECT_EQ(off_sphere, 0);
  }
}

}  // namespace
}  // namespace raylane
