// GGX and Beckman in the lane BSDF (src/render/materials/microfacet_lanes_impl.h) against the
// double Bsdf: the same numbers give the same answers in expectation (paired differences of
// evaluations and of sample weights within their standard error), the lane samples follow the
// double density (chi-square), and Phong rows keep their answers bit for bit when the scene
// also has other distributions.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <optional>

#include "chi2.h"
#include "raylane/core/strings.h"
#include "raylane/render/materials/bsdf.h"
#include "raylane/render/materials/shade_lanes.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sampling.h"
#include "support/estimate.h"

namespace raylane {
namespace {

Material make_material(Microfacet d, glm::vec3 kd, glm::vec3 ks, float alpha,
                       glm::vec3 kt = {0, 0, 0}, float ior = 1) {
  Material m;
  m.kd = kd, m.ks = ks, m.alpha = alpha, m.kt = kt, m.ior = ior, m.microfacet = d;
  return m;
}

// Both distributions, each as a glossy mixture, a sharp white lobe and glass.
std::vector<Material> test_materials() {
  std::vector<Material> out;
  for (Microfacet d : {Microfacet::kGgx, Microfacet::kBeckman}) {
    out.push_back(make_material(d, {0.4f, 0.3f, 0.2f}, {0.3f, 0.3f, 0.3f}, 20));
    out.push_back(make_material(d, {0, 0, 0}, {1, 1, 1}, 2000));
    out.push_back(make_material(d, {0, 0, 0}, {0.04f, 0.04f, 0.04f}, 200, {1, 1, 1}, 1.5f));
  }
  return out;
}

glm::dvec3 column3(const std::array<ShadeBatch::Column, 3>& c, std::size_t i) {
  return {c[0][i], c[1][i], c[2][i]};
}
void set3(std::array<ShadeBatch::Column, 3>& c, std::size_t i, const glm::dvec3& v) {
  for (int k = 0; k < 3; ++k)
    c[k][i] = float(v[k]);
}
glm::dvec3 as_float(const glm::dvec3& v) {
  return normalize(glm::dvec3(glm::vec3(v)));
}

// Rows of one material with one normal and wo, random light directions and numbers.
ShadeBatch batch_of(int material, const glm::dvec3& n, const glm::dvec3& wo, std::size_t rows,
                    uint64_t seed) {
  Rng rng(seed);
  ShadeBatch b;
  b.resize(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    b.material[i] = material;
    set3(b.n, i, n);
    set3(b.wo, i, wo);
    set3(b.light_wi, i, sample_uniform_sphere(rng.uniform(), rng.uniform()));
    b.u_lobe[i] = float(rng.uniform()), b.u1[i] = float(rng.uniform());
    b.u2[i] = float(rng.uniform());
  }
  return b;
}

// ∫ f·cos over the sphere (by the uniform light directions) and the mean sample weight
// value/pdf: each lane figure minus the double figure of the same row, whose mean must be 0
// within 4 standard errors plus float's relative rounding of the figure (64·2^-24).
TEST(MicrofacetLanes, AgreeWithTheDoubleBsdfInExpectation) {
  std::vector<Material> materials = test_materials();
  LaneMaterials lane_materials(materials);
  EXPECT_FALSE(lane_materials.all_phong);
  const glm::dvec3 n = as_float(normalize(glm::dvec3(0.1, -0.2, 1)));
  for (Isa isa : supported_isas())
    for (int mat = 0; mat < int(materials.size()); ++mat)
      for (glm::dvec3 wo0 :
           {glm::dvec3(0.3, 0.1, 1), glm::dvec3(-1, 0.4, 0.35), glm::dvec3(0.2, 0.3, -1)}) {
        glm::dvec3 wo = as_float(normalize(wo0));
        const Material& m = materials[mat];
        SCOPED_TRACE(::testing::Message() << isa_name(isa) << " material " << mat << " "
                                          << microfacet_name(m.microfacet) << " wo.z " << wo.z);
        ShadeBatch b = batch_of(mat, n, wo, 1 << 16, 30 + mat);
        shade_lanes(isa, lane_materials, b);
        Bsdf bsdf(m, n, wo);
        std::size_t i = 0;
        double lane_f = 0, lane_w = 0;
        const int rows = int(b.size());
        testing::Estimate f = testing::estimate(rows, [&] {
          double lane = b.light_f[0][i] * 4 * kPi;
          double ref = bsdf.eval(column3(b.light_wi, i++)).x * 4 * kPi;
          lane_f += lane;
          return lane - ref;
        });
        i = 0;
        testing::Estimate w = testing::estimate(rows, [&] {
          BsdfSample s = bsdf.sample(b.u_lobe[i], b.u1[i], b.u2[i]);
          double lane = b.pdf[i] > 0 ? b.value[0][i] / b.pdf[i] : 0.0;
          ++i;
          lane_w += lane;
          return lane - (s.valid() ? s.value.x / s.pdf : 0.0);
        });
        lane_f /= rows, lane_w /= rows;
        EXPECT_NEAR(f.mean, 0.0, 4 * f.sigma + 64 * 0x1p-24 * lane_f) << "lane ∫f " << lane_f;
        EXPECT_NEAR(w.mean, 0.0, 4 * w.sigma + 64 * 0x1p-24 * lane_w) << "lane weight " << lane_w;
        EXPECT_GT(lane_w, 0.3);  // the rows sample something
      }
}

// The lane sampler's directions against the double density, for a mixture and for glass
// entered and left, of each distribution.
TEST(MicrofacetLanes, SampledDirectionsFollowTheDoubleDensity) {
  std::vector<Material> materials = test_materials();
  LaneMaterials lane_materials(materials);
  const glm::dvec3 n(0, 0, 1);
  struct Case {
    int material;
    glm::dvec3 wo{};
  };
  const Case cases[] = {
      {0, normalize(glm::dvec3(0.5, -0.2, 0.7))}, {2, normalize(glm::dvec3(0.3, 0.1, 1))},
      {2, normalize(glm::dvec3(-0.2, 0.3, -1))},  {3, normalize(glm::dvec3(0.5, -0.2, 0.7))},
      {5, normalize(glm::dvec3(0.3, 0.1, 1))},    {5, normalize(glm::dvec3(-0.2, 0.3, -1))}};
  const double level = testing::sidak_level(0.01, 6);
  for (const Case& c : cases) {
    testing::Chi2Setup setup;
    glm::dvec3 wo = as_float(c.wo);
    ShadeBatch b = batch_of(c.material, n, wo, std::size_t(setup.samples), 50 + c.material);
    shade_lanes(best_isa(), lane_materials, b);
    std::size_t next = 0;
    auto sample = [&](Rng&) -> std::optional<glm::dvec3> {
      std::size_t i = next++;
      if (!(b.pdf[i] > 0)) return std::nullopt;
      return column3(b.wi, i);
    };
    Bsdf bsdf(materials[c.material], n, wo);
    testing::Chi2Result r = testing::chi2_test(
        setup, sample, [&](const glm::dvec3& w) { return bsdf.pdf(w); }, 7);
    EXPECT_FALSE(r.zero_cell_hit);
    EXPECT_GT(r.p_value, level) << "material " << c.material << ": chi2 = " << r.statistic
                                << " with " << r.dof << " dof";
  }
}

// A Phong row's answers do not depend on the other materials of the scene: the same rows of
// Phong materials, shaded with a table that also holds GGX and Beckman materials (whose rows
// are mixed into the batch), give the same bits as with the Phong materials alone.
TEST(MicrofacetLanes, PhongRowsAreBitIdenticalBesideOtherDistributions) {
  const Microfacet phong = Microfacet::kPhong;
  std::vector<Material> phong_only = {
      make_material(phong, {0.4f, 0.3f, 0.2f}, {0.3f, 0.3f, 0.3f}, 30),
      make_material(phong, {0, 0, 0}, {0.04f, 0.04f, 0.04f}, 200, {1, 1, 1}, 1.5f)};
  std::vector<Material> with_others = phong_only;
  with_others.push_back(
      make_material(Microfacet::kGgx, {0.4f, 0.3f, 0.2f}, {0.3f, 0.3f, 0.3f}, 30));
  with_others.push_back(
      make_material(Microfacet::kBeckman, {0, 0, 0}, {0.04f, 0.04f, 0.04f}, 200, {1, 1, 1}, 1.5f));
  LaneMaterials alone(phong_only), mixed(with_others);
  EXPECT_TRUE(alone.all_phong);
  EXPECT_FALSE(mixed.all_phong);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    Rng rng(3);
    ShadeBatch a, m;
    const std::size_t rows = 1001;
    a.resize(rows), m.resize(rows);
    for (std::size_t i = 0; i < rows; ++i) {
      int material = int(rng.uniform() * 2);
      glm::dvec3 ns = sample_uniform_sphere(rng.uniform(), rng.uniform());
      glm::dvec3 wo = sample_uniform_sphere(rng.uniform(), rng.uniform());
      glm::dvec3 light = sample_uniform_sphere(rng.uniform(), rng.uniform());
      float u0 = float(rng.uniform()), u1 = float(rng.uniform()), u2 = float(rng.uniform());
      for (ShadeBatch* b : {&a, &m}) {
        b->material[i] = material;
        set3(b->n, i, as_float(ns)), set3(b->wo, i, as_float(wo)), set3(b->light_wi, i, light);
        b->u_lobe[i] = u0, b->u1[i] = u1, b->u2[i] = u2;
      }
      if (i % 3 == 1) m.material[i] = 2 + material;  // another distribution in every batch
    }
    shade_lanes(isa, alone, a);
    shade_lanes(isa, mixed, m);
    int compared = 0;
    for (std::size_t i = 0; i < rows; ++i) {
      if (m.material[i] != a.material[i]) continue;
      ++compared;
      for (auto c : {&ShadeBatch::wi, &ShadeBatch::value, &ShadeBatch::light_f})
        for (int k = 0; k < 3; ++k)
          ASSERT_EQ(std::bit_cast<uint32_t>((a.*c)[k][i]), std::bit_cast<uint32_t>((m.*c)[k][i]))
              << "row " << i;
      ASSERT_EQ(std::bit_cast<uint32_t>(a.pdf[i]), std::bit_cast<uint32_t>(m.pdf[i])) << i;
      ASSERT_EQ(std::bit_cast<uint32_t>(a.light_pdf[i]), std::bit_cast<uint32_t>(m.light_pdf[i]))
          << i;
    }
    EXPECT_GT(compared, 600);
  }
}

}  // namespace
}  // namespace raylane
