// The course's BSDF: sample(), eval() and pdf() agree; Lambert is exact; the Phong lobe's
// albedo stays within Kd + Ks (docs/hard-cases.md M2); corner inputs give no NaN (N6).
#include <gtest/gtest.h>

#include <cmath>

#include "raylane/render/materials/bsdf.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sampling.h"
#include "support/estimate.h"

namespace raylane {
namespace {

Material make_material(glm::vec3 kd, glm::vec3 ks, float alpha, glm::vec3 kt = {0, 0, 0},
                       float ior = 1) {
  Material m;
  m.kd = kd, m.ks = ks, m.alpha = alpha, m.kt = kt, m.ior = ior;
  return m;
}

const glm::dvec3 kN(0, 0, 1);

glm::dvec3 direction_at(double cos_theta, double phi = 0.7) {
  double s = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

using testing::Estimate;
using testing::estimate;

// Albedo (channel 0) of f·cos/pdf by importance sampling, and the same integral of eval() by
// uniform sphere sampling: two estimators of one number, which agree only if sample, eval and
// pdf agree. Also ∫pdf over the sphere equals the fraction of valid samples.
TEST(Bsdf, SampleEvalAndPdfAgree) {
  const Material materials[] = {
      make_material({0.7f, 0.7f, 0.7f}, {0, 0, 0}, 0),
      make_material({0, 0, 0}, {0.8f, 0.8f, 0.8f}, 5),
      make_material({0.4f, 0.3f, 0.2f}, {0.3f, 0.3f, 0.3f}, 10),
      make_material({0, 0, 0}, {0.04f, 0.04f, 0.04f}, 8, {1, 1, 1}, 1.5f),
  };
  Rng rng(7);
  for (const Material& m : materials) {
    for (glm::dvec3 wo : {direction_at(0.9), direction_at(0.3), direction_at(-0.6)}) {
      Bsdf bsdf(m, kN, wo);
      const int n = 200000;
      int valid = 0;
      Estimate is = estimate(n, [&] {
        BsdfSample s = bsdf.sample(rng.uniform(), rng.uniform(), rng.uniform());
        if (!s.valid()) return 0.0;
        ++valid;
        return s.value.x / s.pdf;
      });
      Estimate uni_f = estimate(n, [&] {
        glm::dvec3 wi = sample_uniform_sphere(rng.uniform(), rng.uniform());
        return bsdf.eval(wi).x * 4 * kPi;
      });
      Estimate uni_pdf = estimate(n, [&] {
        glm::dvec3 wi = sample_uniform_sphere(rng.uniform(), rng.uniform());
        return bsdf.pdf(wi) * 4 * kPi;
      });
      SCOPED_TRACE(::testing::Message()
                   << "kd " << m.kd.x << " ks " << m.ks.x << " kt " << m.kt.x << " cos_o " << wo.z);
      EXPECT_NEAR(is.mean, uni_f.mean, 4 * std::hypot(is.sigma, uni_f.sigma));
      double frac = double(valid) / n, frac_sigma = std::sqrt(frac * (1 - frac) / n);
      EXPECT_NEAR(uni_pdf.mean, frac, 4 * std::hypot(uni_pdf.sigma, frac_sigma));
    }
  }
}

// Cosine sampling of a Lambertian surface has zero variance: every weight is Kd
// (docs/hard-cases.md M1: |L − ρ| ≤ 1e-5 where the estimator is deterministic).
TEST(Bsdf, LambertWeightIsExactlyKd) {
  Bsdf bsdf(make_material({0.5f, 0.25f, 1}, {0, 0, 0}, 0), kN, direction_at(0.4));
  Rng rng(3);
  for (int i = 0; i < 10000; ++i) {
    BsdfSample s = bsdf.sample(rng.uniform(), rng.uniform(), rng.uniform());
    if (!s.valid()) continue;
    glm::dvec3 w = s.value / s.pdf;
    EXPECT_NEAR(w.x, 0.5, 1e-12);
    EXPECT_NEAR(w.y, 0.25, 1e-12);
    EXPECT_NEAR(w.z, 1.0, 1e-12);
  }
}

// The "weak white furnace" of the microfacet model (Heitz 2014, "Understanding the
// Masking-Shadowing Function in Microfacet-Based BRDFs", §7.1): W = ∫ D(m)·G1(o, m)·⟨o·m⟩ dm /
// cos θo, an upper bound on the reflection lobe's albedo for any F ≤ 1 and G2 ≤ G1. It is 1
// for the exact Smith G1 of D; the course's G1 is the rational fit for Beckmann, which does
// not match the Phong lobe, so W exceeds 1 for rough lobes at grazing angles.
Estimate weak_furnace(double alpha, double cos_o, Rng& rng) {
  glm::dvec3 o = direction_at(cos_o);
  return estimate(65536, [&] {
    glm::dvec3 h = sample_phong_normal(rng.uniform(), rng.uniform(), alpha);
    double om = dot(o, h), pm = phong_normal_pdf(h.z, alpha);
    if (!(om > 0) || !(pm > 0)) return 0.0;
    // G1(o, h) by the rational approximation, written out independently of bsdf.cpp.
    double s = std::sqrt(std::max(0.0, 1 - cos_o * cos_o));
    double a = s > 0 ? std::sqrt(0.5 * alpha + 1) * cos_o / s : 2.0;
    double g1 = a > 1.6 ? 1.0 : (3.535 * a + 2.181 * a * a) / (1 + 2.276 * a + 2.577 * a * a);
    return phong_d(h.z, alpha) * g1 * om / (cos_o * pm);
  });
}

Estimate albedo(const Material& m, double cos_o, Rng& rng) {
  Bsdf bsdf(m, kN, direction_at(cos_o));
  return estimate(16384, [&] {
    BsdfSample s = bsdf.sample(rng.uniform(), rng.uniform(), rng.uniform());
    return s.valid() ? s.value.x / s.pdf : 0.0;
  });
}

// pbrt-v4 TestEnergyConservation's setup (16384 samples of f·cos/pdf per outgoing direction,
// n ∈ {1, 10, 100, 1e4}). What holds for the course's model, and is asserted:
// - the reflection lobe's albedo ≤ W, the weak-furnace bound above (W ≤ 1 + 4σ for α ≥ 100);
// - at normal incidence, where Schlick's F equals Ks: albedo ≤ Kd + Ks·W.
// What does NOT hold (measured, see the report): "albedo ≤ Kd + Ks ≤ 1 at any angle". The
// rational G gives W = 1.35 at α = 1, cos θo = 0.05; and Schlick's F rises to 1 at grazing
// while the diffuse lobe keeps Kd, so Kd = 0.3, Ks = 0.7, α = 1e4 reflects 1.23 at cos 0.05.
TEST(Bsdf, PhongLobeAlbedoIsBounded) {
  Rng rng(11);
  for (double alpha : {1.0, 10.0, 100.0, 1e4}) {
    Material glossy = make_material({0, 0, 0}, {1, 1, 1}, float(alpha));
    Material mixed = make_material({0.3f, 0.3f, 0.3f}, {0.7f, 0.7f, 0.7f}, float(alpha));
    for (double c : {1.0, 0.7, 0.4, 0.15, 0.05}) {
      SCOPED_TRACE(::testing::Message() << "alpha " << alpha << " cos_o " << c);
      Estimate e = albedo(glossy, c, rng), w = weak_furnace(alpha, c, rng);
      EXPECT_LE(e.mean, w.mean + 4 * std::hypot(e.sigma, w.sigma));
      if (alpha >= 100) {  // 0.005: the G fit's excess at α = 100, cos θo = 0.05
        EXPECT_LE(w.mean, 1 + 4 * w.sigma + 0.005);
      }
      EXPECT_GE(e.mean, 0.5);  // a white lobe loses at most G's and the horizon's share
    }
    Estimate normal = albedo(mixed, 1.0, rng), w = weak_furnace(alpha, 1.0, rng);
    EXPECT_LE(normal.mean, 0.3 + 0.7 * w.mean + 4 * std::hypot(normal.sigma, 0.7 * w.sigma))
        << "alpha " << alpha;
  }
}

// No NaN or inf at the corners of the unit cube of random numbers, for α up to 1e4, every
// microfacet distribution, index-matched glass included, and outgoing directions down to
// grazing (docs/hard-cases.md N6); pdf-0 samples are reported invalid.
TEST(Bsdf, CornerSamplesAreFinite) {
  const double us[] = {0.0, 0x1p-53, 0.5, 1 - 0x1p-24, 1 - 0x1p-53, 1.0};
  int invalid = 0, total = 0;
  for (float alpha : {0.0f, 1.0f, 1e4f})
    for (Material m : {make_material({0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}, alpha),
                       make_material({0, 0, 0}, {0.04f, 0.04f, 0.04f}, alpha, {1, 1, 1}, 1.5f),
                       make_material({0, 0, 0}, {0, 0, 0}, alpha, {1, 1, 1}, 1.0f)})
      for (Microfacet d : {Microfacet::kPhong, Microfacet::kGgx, Microfacet::kBeckman})
        for (double c : {1.0, 1e-3, -1e-3, -1.0}) {
          m.microfacet = d;
          Bsdf bsdf(m, kN, direction_at(c));
          for (double u0 : us)
            for (double u1 : us)
              for (double u2 : us) {
                BsdfSample s = bsdf.sample(u0, u1, u2);
                ++total;
                if (!s.valid()) {
                  ++invalid;
                  continue;
                }
                ASSERT_TRUE(std::isfinite(s.pdf) && is_finite(s.value) && is_finite(s.wi));
                ASSERT_TRUE(is_finite(s.value / s.pdf));
              }
        }
  EXPECT_LT(invalid, total);
}

}  // namespace
}  // namespace raylane
