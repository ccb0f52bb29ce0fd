// GGX and Beckman (render/materials/microfacet.h) in the double reference Bsdf: D is normalised,
// the sampler follows the pdf (chi-square over the sphere), the white furnace (Ks = 1, Kd = 0)
// reflects at most all and as much as quadrature of the same BRDF says, the BSDF is reciprocal,
// and index-matched glass weighs its Dirac lobe right (corner inputs: bsdf_test.cpp).
// docs/microfacet.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "chi2.h"
#include "raylane/render/materials/bsdf.h"
#include "raylane/render/materials/microfacet.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sampling.h"
#include "support/estimate.h"

namespace raylane {
namespace {

using testing::Estimate;
using testing::estimate;

constexpr Microfacet kDistributions[] = {Microfacet::kGgx, Microfacet::kBeckman};

Material make_material(Microfacet d, glm::vec3 kd, glm::vec3 ks, float alpha,
                       glm::vec3 kt = {0, 0, 0}, float ior = 1) {
  Material m;
  m.kd = kd, m.ks = ks, m.alpha = alpha, m.kt = kt, m.ior = ior, m.microfacet = d;
  return m;
}

glm::dvec3 direction_at(double cos_theta, double phi = 0.7) {
  double s = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

// A quadrature over the microfacet normals m of the hemisphere, by the midpoint rule in
// (s, φ) with θm = atan(α_g·tan(πs/2)): the points gather where D has its mass, for any α_g.
// f(m, dω) receives each point's solid angle.
template <class F>
double quadrature_over_normals(double alpha_g, int nt, int nphi, F&& f) {
  double sum = 0;
  for (int i = 0; i < nt; ++i) {
    double s = (i + 0.5) / nt, x = std::tan(0.5 * kPi * s);
    double theta = std::atan(alpha_g * x);
    double dtheta = alpha_g * 0.5 * kPi * (1 + x * x) / (1 + alpha_g * alpha_g * x * x) / nt;
    for (int j = 0; j < nphi; ++j) {
      double phi = 2 * kPi * (j + 0.5) / nphi;
      glm::dvec3 m(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta));
      sum += f(m, std::sin(theta) * dtheta * 2 * kPi / nphi);
    }
  }
  return sum;
}

double d_of(Microfacet d, double cos_m, double alpha_g) {
  return d == Microfacet::kGgx ? ggx_d(cos_m, alpha_g) : beckman_d(cos_m, alpha_g);
}

// ∫ D(m)·cos θm dm = 1: the projected microfacet area is the surface's (Walter eq. 4).
TEST(Microfacet, DistributionsAreNormalised) {
  for (Microfacet d : kDistributions)
    for (double alpha : {0.0, 1.0, 20.0, 200.0, 2000.0, 1e5}) {
      double ag = microfacet_alpha_g(alpha);
      double area = quadrature_over_normals(
          ag, 4000, 1, [&](const glm::dvec3& m, double dw) { return d_of(d, m.z, ag) * m.z * dw; });
      EXPECT_NEAR(area, 1.0, 1e-5) << microfacet_name(d) << " alpha " << alpha;
    }
  EXPECT_NEAR(microfacet_alpha_g(0), 1.0, 1e-15);
  EXPECT_NEAR(microfacet_alpha_g(2000), std::sqrt(2.0 / 2002), 1e-15);
}

// Every chi-square run of this file shares one family-wise level of 1 % (Šidák).
constexpr int kChi2Runs = 12;
const double kLevel = testing::sidak_level(0.01, kChi2Runs);

testing::Chi2Result bsdf_chi2(const Material& m, const glm::dvec3& wo, const glm::dvec3& axis,
                              double z_min, uint64_t seed) {
  Bsdf bsdf(m, glm::dvec3(0, 0, 1), wo);
  testing::Chi2Setup setup;
  setup.axis = axis;
  setup.z_min = z_min;
  auto sample = [&](Rng& rng) -> std::optional<glm::dvec3> {
    BsdfSample s = bsdf.sample(rng.uniform(), rng.uniform(), rng.uniform());
    if (!s.valid()) return std::nullopt;
    return s.wi;
  };
  return testing::chi2_test(
      setup, sample, [&](const glm::dvec3& w) { return bsdf.pdf(w); }, seed);
}

void expect_fits(const testing::Chi2Result& r) {
  EXPECT_FALSE(r.zero_cell_hit);
  EXPECT_GT(r.p_value, kLevel) << "chi2 = " << r.statistic << " with " << r.dof << " dof";
}

// The reflection lobe around the mirror direction (binned over the cap where it has its mass,
// the rest in the chi-square's outside cell), and glass entered and left.
TEST(MicrofacetBsdf, SamplesFollowThePdf) {
  uint64_t seed = 100;
  for (Microfacet d : kDistributions) {
    for (double alpha : {10.0, 1000.0})
      for (glm::dvec3 wo :
           {normalize(glm::dvec3(0.3, 0.1, 1)), normalize(glm::dvec3(-1, 0.4, 0.5))}) {
        SCOPED_TRACE(::testing::Message()
                     << microfacet_name(d) << " alpha " << alpha << " wo.z " << wo.z);
        Material m = make_material(d, {0, 0, 0}, {1, 1, 1}, float(alpha));
        double z_min = std::max(-1.0, 1 - 60 / (alpha + 1));
        expect_fits(bsdf_chi2(m, wo, glm::dvec3(-wo.x, -wo.y, wo.z), z_min, ++seed));
      }
    SCOPED_TRACE(microfacet_name(d));
    Material glass = make_material(d, {0, 0, 0}, {0.04f, 0.04f, 0.04f}, 20, {1, 1, 1}, 1.5f);
    expect_fits(
        bsdf_chi2(glass, normalize(glm::dvec3(0.6, 0, 0.8)), glm::dvec3(0.1, 0.2, 1), -1, ++seed));
    expect_fits(bsdf_chi2(glass, normalize(glm::dvec3(0.5, 0.1, -0.6)), glm::dvec3(0.1, 0.2, 1), -1,
                          ++seed));
  }
}

// The single-scattering albedo of a white lobe (F = Ks = 1 by Schlick at any angle) by
// quadrature over m: wi = reflect(wo, m), dωi = 4(wo·m)·dωm, so ∫ f·cos θi dωi =
// ∫ eval(reflect(wo, m))·4(wo·m) dωm over the m that face wo.
double quadrature_albedo(const Bsdf& bsdf, const glm::dvec3& wo, double alpha_g, int n) {
  return quadrature_over_normals(alpha_g, n, n / 2, [&](const glm::dvec3& m, double dw) {
    double om = dot(wo, m);
    if (!(om > 0)) return 0.0;
    return bsdf.eval(2 * om * m - wo).x * 4 * om * dw;
  });
}

// White furnace: Kd = 0, Ks = 1. GGX's G1 is Smith's exact one, so ∫D·G1(o)·(o·m)/cos θo = 1
// and the albedo, with G = G1(i)·G1(o) ≤ G1(o), is at most 1; Beckman's rational G1 is within
// 0.35 % of Smith's (Walter et al. §5.1), which the bound allows. The importance-sampled
// albedo (65536 samples) must equal the quadrature within 4σ plus the quadrature's own error,
// taken as its change from n = 400 to 800 points per axis.
TEST(MicrofacetBsdf, WhiteFurnaceAlbedoIsAtMostOneAndMatchesQuadrature) {
  Rng rng(21);
  std::printf("distribution  alpha  cos_o  sampled (sigma)      quadrature (error)\n");
  for (Microfacet d : kDistributions)
    for (double alpha : {20.0, 200.0, 2000.0})
      for (double c : {1.0, 0.7, 0.4, 0.15}) {
        SCOPED_TRACE(::testing::Message()
                     << microfacet_name(d) << " alpha " << alpha << " cos_o " << c);
        Material m = make_material(d, {0, 0, 0}, {1, 1, 1}, float(alpha));
        glm::dvec3 wo = direction_at(c);
        Bsdf bsdf(m, glm::dvec3(0, 0, 1), wo);
        Estimate e = estimate(65536, [&] {
          BsdfSample s = bsdf.sample(rng.uniform(), rng.uniform(), rng.uniform());
          return s.valid() ? s.value.x / s.pdf : 0.0;
        });
        double ag = microfacet_alpha_g(float(alpha));
        double q = quadrature_albedo(bsdf, wo, ag, 800);
        double q_err = std::abs(q - quadrature_albedo(bsdf, wo, ag, 400));
        std::printf("%-12s %6g %6g  %.6f (%.1e)  %.6f (%.1e)\n", microfacet_name(d), alpha, c,
                    e.mean, e.sigma, q, q_err);
        EXPECT_LE(e.mean, 1 + 4 * e.sigma);
        EXPECT_LE(q, 1 + q_err);
        EXPECT_NEAR(e.mean, q, 4 * e.sigma + q_err);
        EXPECT_GT(q, 0.5);  // a white lobe loses at most G's and the horizon's share
      }
}

// f(wo, wi) = f(wi, wo) for reflection (eval is f·|cos θi|). For transmission, Walter's BTDF
// (eq. 21) is reciprocal up to the indices and Fresnel: f(wo, wi)/(η_o²·(1 − F(wo·m))) =
// f(wi, wo)/(η_i²·(1 − F(wi·m))), with η_o the index on wo's side; Schlick's F is taken at the
// viewer's side each way, so it is divided out.
TEST(MicrofacetBsdf, IsReciprocal) {
  const glm::dvec3 n(0, 0, 1);
  Rng rng(5);
  int transmissions = 0;
  for (Microfacet d : kDistributions) {
    Material m = make_material(d, {0.2f, 0.3f, 0.1f}, {0.3f, 0.2f, 0.5f}, 30, {1, 1, 1}, 1.5f);
    for (int i = 0; i < 2000; ++i) {
      glm::dvec3 a = sample_uniform_sphere(rng.uniform(), rng.uniform());
      glm::dvec3 b = sample_uniform_sphere(rng.uniform(), rng.uniform());
      if (std::abs(a.z) < 1e-3 || std::abs(b.z) < 1e-3) continue;
      glm::dvec3 fab = Bsdf(m, n, a).eval(b) / std::abs(b.z),
                 fba = Bsdf(m, n, b).eval(a) / std::abs(a.z);
      if (a.z * b.z < 0) {
        double eta_a = a.z > 0 ? 1 : 1.5, eta_b = b.z > 0 ? 1 : 1.5;
        glm::dvec3 h = -(a * eta_a + b * eta_b);
        glm::dvec3 mf = normalize(h);
        auto schlick = [&](int k, double c) {
          double ks = m.ks[k], x = 1 - std::abs(c);
          return ks + (1 - ks) * x * x * x * x * x;
        };
        for (int k = 0; k < 3; ++k) {
          fab[k] /= eta_a * eta_a * (1 - schlick(k, dot(a, mf)));
          fba[k] /= eta_b * eta_b * (1 - schlick(k, dot(b, mf)));
        }
        transmissions += fab.x > 0;
      }
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(fab[k], fba[k], 1e-9 * std::max(1.0, std::abs(fab[k])))
            << microfacet_name(d) << " channel " << k << " a.z " << a.z << " b.z " << b.z;
    }
  }
  EXPECT_GT(transmissions, 100);
}

// Index-matched glass (η = 1) is a Dirac lobe whose weight is the limit of the regular
// estimator: its mean over m at normal incidence is the transmitted fraction
// E[(1 − F)·G·(wo·m)/cos θo·D/p(m)] with Ks = 0, computed here by quadrature.
TEST(MicrofacetBsdf, IndexMatchedWeightIsTheLimitOfRefraction) {
  Rng rng(9);
  for (Microfacet d : kDistributions) {
    Material m = make_material(d, {0, 0, 0}, {0, 0, 0}, 50, {1, 1, 1}, 1.0f);
    Bsdf bsdf(m, glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1));
    Estimate e = estimate(65536, [&] {
      BsdfSample s = bsdf.sample(rng.uniform(), rng.uniform(), rng.uniform());
      EXPECT_TRUE(!s.valid() || s.specular);
      return s.valid() ? s.value.x / s.pdf : 0.0;
    });
    double ag = microfacet_alpha_g(50);
    // G = G1(wo)·G1(−wo) = G1(wo, m)², 1 − F = 1 − (1 − wo·m)^5, wo = n: wo·m = cos θm.
    double expected = quadrature_over_normals(ag, 4000, 1, [&](const glm::dvec3& mf, double dw) {
      double g1 = d == Microfacet::kGgx ? ggx_g1(1, mf.z, ag) : beckman_g1(1, mf.z, ag);
      return d_of(d, mf.z, ag) * mf.z * (1 - std::pow(1 - mf.z, 5)) * g1 * g1 * dw;
    });
    EXPECT_NEAR(e.mean, expected, 4 * e.sigma + 1e-6) << microfacet_name(d);
  }
}

}  // namespace
}  // namespace raylane
