// Importance sampling of the environment light (render/lights/environment.h) against its density:
// chi-square fits (docs/hard-cases.md M4), sample/pdf agreement, ∫pdf dω = 1, and the
// estimator check: irradiance by importance and by uniform sampling against a quadrature.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "chi2.h"
#include "env_maps.h"
#include "raylane/render/lights/environment.h"
#include "raylane/render/samplers/rng.h"
#include "support/estimate.h"
#include "support/same_bits.h"

namespace raylane {
namespace {

using testing::Estimate;
using testing::estimate;
using testing::same_bits;

constexpr double kBelowOne = 0x1.fffffffffffffp-1;

// Every chi-square run of this file shares one family-wise level of 1 % (Šidák).
constexpr int kChi2Runs = 6;
const double kLevel = testing::sidak_level(0.01, kChi2Runs);

// Rᵀ·w: a world direction back in the image's frame.
glm::dvec3 to_image(const glm::dmat3& r, const glm::dvec3& w) {
  return glm::transpose(r) * w;
}

glm::dmat3 tilted() {
  return rotation_axis_angle(normalize(glm::dvec3(1, 2, 3)), 50);
}

// Binned around an axis away from every test rotation's poles: the density grows as 1/sin θ
// toward the image's poles, and with a pole on the binning axis the helper's 24×24 midpoint
// sub-samples under-integrate the cap's bins by ~1.4 %, a deficit it books as expected invalid
// samples (enough to fail a correct sampler). Away from the axis a pole is a point inside a
// bin, where the midpoint rule's error is negligible. 200,000 samples keep the remaining
// quadrature error at the sun's edges (~20 of chi-square) well inside the noise.
void expect_fits(const EnvironmentMap& env, uint64_t seed) {
  testing::Chi2Setup setup;
  setup.axis = normalize(glm::dvec3(1, -2, 0.5));
  setup.samples = 200'000;
  auto sample = [&](Rng& rng) -> std::optional<glm::dvec3> {
    double u1 = rng.uniform(), u2 = rng.uniform();
    EnvironmentSample s = env.sample(u1, u2);
    if (!s.valid()) return std::nullopt;
    return s.wi;
  };
  auto pdf = [&](const glm::dvec3& w) { return env.pdf(w); };
  testing::Chi2Result r = testing::chi2_test(setup, sample, pdf, seed);
  EXPECT_FALSE(r.zero_cell_hit);
  EXPECT_GT(r.p_value, kLevel) << "chi2 = " << r.statistic << " with " << r.dof << " dof";
}

// The cell a CDF inversion must land in: the i with cdf[i] ≤ U < cdf[i + 1] for U = ⌊u·kUnits⌋,
// the CDF being the running sums of the table's own steps (pdf_of_cell · kUnits / n, exact),
// found by a linear scan.
uint32_t cell_by_scan(const PiecewiseConstant1D& d, double u) {
  const double units = std::floor(u * PiecewiseConstant1D::kUnits), n = d.size();
  double sum = 0;
  uint32_t last = 0;
  for (uint32_t i = 0; i < d.size(); ++i) {
    const double step = d.pdf_of_cell(i) * PiecewiseConstant1D::kUnits / n;
    if (sum <= units && step > 0) last = i;
    sum += step;
  }
  return last;
}

// The steps the table gives the weights: each within 2k + 1 units of the weight's share of
// kUnits (k cells of weight > 0: rounding moves an end by half a unit, and the lifts that give a
// tiny cell its unit move the ends after it, and the backward pass those before, by at most one
// unit each); every cell of weight > 0 has a step, every other none.
void expect_steps_follow_weights(const PiecewiseConstant1D& d, const std::vector<double>& f) {
  double total = 0, lit = 0;
  for (double w : f)
    total += w, lit += w > 0;
  const double n = d.size();
  for (uint32_t i = 0; i < d.size(); ++i) {
    const double step = d.pdf_of_cell(i) * PiecewiseConstant1D::kUnits / n;
    EXPECT_NEAR(step, f[i] / total * PiecewiseConstant1D::kUnits, 2 * lit + 1) << "cell " << i;
    EXPECT_EQ(step > 0, f[i] > 0) << "cell " << i;
  }
}

// The guide table (render/lights/environment.h) only narrows the search: every u lands in the cell
// a scan of the whole CDF finds, for weights with empty cells, one spike holding almost all the
// weight (many cells between two guide entries), and any size; u at every CDF step, just below
// it, and at random.
TEST(EnvironmentSampling, GuidedInversionFindsTheScansCell) {
  Rng rng(42);
  for (uint32_t n : {1u, 2u, 3u, 5u, 17u, 64u, 1000u}) {
    for (int shape = 0; shape < 3; ++shape) {
      std::vector<double> f(n);
      for (uint32_t i = 0; i < n; ++i) {
        double w = rng.uniform();
        f[i] = shape == 1 && rng.uniform() < 0.5 ? 0.0 : w;
        if (shape == 2) f[i] = i == n / 2 ? 1e6 : 1e-3 * w;
      }
      if (std::all_of(f.begin(), f.end(), [](double w) { return w == 0; })) f[0] = 1;
      PiecewiseConstant1D d(f);
      expect_steps_follow_weights(d, f);
      std::vector<double> us;
      double sum = 0;
      for (uint32_t i = 0; i < n; ++i) {
        sum += d.pdf_of_cell(i) / n;  // the table's CDF, exactly
        us.push_back(sum), us.push_back(std::nextafter(sum, 0.0));
      }
      for (int k = 0; k < 2000; ++k)
        us.push_back(rng.uniform());
      us.push_back(0.0), us.push_back(kBelowOne);
      for (double u : us) {
        if (!(u < 1)) continue;
        uint32_t cell = 0;
        double pdf = 0;
        d.sample_continuous(u, &pdf, &cell);
        ASSERT_EQ(cell, cell_by_scan(d, u)) << "n " << n << " shape " << shape << " u " << u;
        ASSERT_GT(pdf, 0);
      }
    }
  }
}

TEST(EnvironmentSampling, SunMapFollowsItsPdf) {
  // A sun 125 times the sky's brightness: ~40 % of the samples land in its 3×3 cells.
  expect_fits(EnvironmentMap(testing::sun_map(50), 1, glm::dmat3(1.0)), 1);
  expect_fits(EnvironmentMap(testing::sun_map(50), 1, tilted()), 2);
  expect_fits(EnvironmentMap(testing::sun_map(50), 1, rotation_axis_angle({0, 1, 0}, 90)), 3);
}

TEST(EnvironmentSampling, GradientMapFollowsItsPdf) {
  expect_fits(EnvironmentMap(testing::gradient_map(), 1, glm::dmat3(1.0)), 4);
  expect_fits(EnvironmentMap(testing::gradient_map(), 1, tilted()), 5);
  expect_fits(EnvironmentMap(testing::gradient_map(), 1, rotation_axis_angle({1, 0, 0}, 120)), 6);
}

// Whether image coordinate c·n lies within 1e-7 of a cell edge, where a direction's round trip
// may land in the neighbouring cell.
bool near_edge(double c, uint32_t n) {
  double t = c * n;
  return std::abs(t - std::round(t)) < 1e-7;
}

TEST(EnvironmentSampling, PdfOfTheSampleIsTheSamplesPdf) {
  glm::dmat3 r = tilted();
  EnvironmentMap env(testing::sun_map(1000), 2, r);
  Rng rng(11);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    EnvironmentSample s = env.sample(rng.uniform(), rng.uniform());
    ASSERT_TRUE(s.valid());
    ASSERT_NEAR(length(s.wi), 1, 1e-14);
    // The image point of wi (Rᵀ·wi), to skip the cell edges.
    glm::dvec3 d = to_image(r, s.wi);
    double phi = std::atan2(d.y, d.x), v = std::acos(std::clamp(d.z, -1.0, 1.0)) / kPi;
    double u = (phi < 0 ? phi + 2 * kPi : phi) / (2 * kPi);
    if (near_edge(u, env.width()) || near_edge(v, env.height())) continue;
    ++checked;
    ASSERT_NEAR(env.pdf(s.wi), s.pdf, 1e-9 * s.pdf) << "u = " << u << ", v = " << v;
    glm::dvec3 le = env.radiance(s.wi);
    ASSERT_NEAR(le.x, s.le.x, 1e-9 * (1 + le.x));
  }
  EXPECT_GT(checked, 199000);
}

// sample_many reads the tables a stage at a time across its rows, with prefetches ahead: its
// answers are sample()'s, row by row, bit for bit, for a batch that crosses the map's rows many
// times over and holds the edge numbers 0 and just below 1.
TEST(EnvironmentSampling, ManySamplesAreTheOneByOneSamples) {
  EnvironmentMap env(testing::sun_map(1000), 2, tilted());
  Rng rng(12);
  EnvironmentBatch b;
  b.resize(5000);
  for (std::size_t i = 0; i < b.u1.size(); ++i)
    b.u1[i] = rng.uniform(), b.u2[i] = rng.uniform();
  b.u1[0] = 0, b.u2[0] = 0, b.u1[1] = kBelowOne, b.u2[1] = kBelowOne;
  env.sample_many(b);
  for (std::size_t i = 0; i < b.u1.size(); ++i) {
    const EnvironmentSample want = env.sample(b.u1[i], b.u2[i]);
    const EnvironmentSample& got = b.out[i];
    ASSERT_TRUE(want.wi == got.wi && want.le == got.le && want.pdf == got.pdf) << "row " << i;
  }
}

// seen_many looks up its rows with prefetches ahead: its answers are seen()'s, row by row, bit
// for bit, for directions of every length (unit ones, long and short ones, a zero vector and a
// NaN) and the poles, under a map that samples and one that does not.
TEST(EnvironmentSampling, ManySeenAreTheOneByOneSeen) {
  Image black(4, 2);
  for (const EnvironmentMap& env : {EnvironmentMap(testing::sun_map(1000), 2, tilted()),
                                    EnvironmentMap(black, 1, glm::dmat3(1.0))}) {
    Rng rng(13);
    EnvironmentSeenBatch b;
    for (int i = 0; i < 3000; ++i) {
      const glm::dvec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
      b.dir.push_back(i % 3 == 0 ? d * (1e-3 + 1e3 * rng.uniform()) : d);
    }
    b.dir[7] = glm::dvec3(0, 0, 0), b.dir[8] = glm::dvec3(std::nan(""), 0, 1);
    b.dir[9] = env.rotation() * glm::dvec3(0, 0, 1), b.dir[10] = -b.dir[9];
    env.seen_many(b);
    ASSERT_EQ(b.seen.size(), b.dir.size());
    int lit = 0;
    for (std::size_t i = 0; i < b.dir.size(); ++i) {
      const EnvironmentMap::Seen want = env.seen(b.dir[i]);
      const EnvironmentMap::Seen& got = b.seen[i];
      ASSERT_TRUE(same_bits(want.le, got.le) && same_bits(want.pdf, got.pdf)) << "row " << i;
      lit += got.pdf > 0;
    }
    EXPECT_EQ(lit > 0, env.can_sample());
  }
}

TEST(EnvironmentSampling, EdgeNumbersAndPolesGiveNoNaN) {
  // A bright top row, so the pole's cells are sampled: u2 = 0 lands exactly on the pole.
  Image img = testing::make_image(8, 4, [](uint32_t x, uint32_t y) {
    return y == 0 ? glm::vec3(5, 5, 5) : glm::vec3(float(x) * 0.1f, 0, 0);
  });
  EnvironmentMap env(img, 1, tilted());
  for (double u1 : {0.0, 1e-300, 0.5, kBelowOne, 1.0})
    for (double u2 : {0.0, 1e-300, 0.5, kBelowOne, 1.0}) {
      EnvironmentSample s = env.sample(u1, u2);
      ASSERT_TRUE(is_finite(s.wi) && is_finite(s.le) && std::isfinite(s.pdf)) << u1 << " " << u2;
      // Within ~1e-16 of a pole the world direction cannot resolve sin θ (the density's
      // 1/sin θ): agreement is asked for where it can.
      glm::dvec3 d = to_image(env.rotation(), s.wi);
      if (s.valid() && std::hypot(d.x, d.y) > 1e-6) {
        EXPECT_NEAR(env.pdf(s.wi), s.pdf, 1e-9 * s.pdf) << u1 << " " << u2;
      }
    }
  EXPECT_FALSE(env.sample(0.3, 0.0).valid());  // exactly the pole: sin θ = 0
  for (glm::dvec3 d :
       {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), env.rotation() * glm::dvec3(0, 0, 1),
        env.rotation() * glm::dvec3(0, 0, -1), glm::dvec3(0, 0, 0), glm::dvec3(NAN, 0, 1)}) {
    EXPECT_TRUE(std::isfinite(env.pdf(d)));
    EXPECT_TRUE(is_finite(env.radiance(d)));
  }
}

// ∫ pdf dω = 1: the mean of 4π·pdf over uniform directions.
TEST(EnvironmentSampling, PdfIntegratesToOne) {
  for (const EnvironmentMap& env : {EnvironmentMap(testing::sun_map(50), 1, tilted()),
                                    EnvironmentMap(testing::gradient_map(), 3, tilted())}) {
    Rng rng(5);
    Estimate e = estimate(400000, [&] {
      return 4 * kPi * env.pdf(sample_uniform_sphere(rng.uniform(), rng.uniform()));
    });
    EXPECT_NEAR(e.mean, 1, 4 * e.sigma);
    EXPECT_LT(e.sigma, 0.02);  // so the check has teeth
  }
}

// Irradiance on an upward plane, E = ∫ lum(L(ω))·max(0, ω_z) dω, by a midpoint quadrature of
// the bilinear map over the image (8×8 sub-cells a texel, meeting at the texel centres).
double irradiance_quadrature(const EnvironmentMap& env) {
  const int nu = env.width() * 8, nv = env.height() * 8;
  double sum = 0;
  for (int j = 0; j < nv; ++j) {
    double v = (j + 0.5) / nv;
    for (int i = 0; i < nu; ++i) {
      glm::dvec3 w = env.rotation() * testing::direction_of((i + 0.5) / nu, v);
      if (w.z > 0) sum += rec709_luminance(env.radiance(w)) * w.z * std::sin(kPi * v);
    }
  }
  return sum * 2 * kPi * kPi / (double(nu) * nv);
}

// The same integral by importance sampling and by uniform directions agree with the quadrature
// within 4σ, and importance sampling must beat uniform sampling by far. The sun (2×2 texels of
// 64×32, its bilinear lookup spread over 3×3 texels' worth, ≈ 0.6 % of the sphere, at
// 20,000 times the sky) gives nearly all of E, so uniform directions find it about once in
// 175 draws: by Cauchy–Schwarz their variance is at least E²·(1/0.006 − 1) ≈ 170·E². The
// importance weights lum·cos/pdf vary only with the tent's shape inside the piecewise-constant
// cells and with cos θ, a spread of order E (measured: σ ≈ 0.8·E a sample). A ratio of 10 is far
// below what a correct sampler reaches and far above what sampling blind to the sun gets (~1).
TEST(EnvironmentSampling, ImportanceSamplingEstimatesIrradianceWithLessVariance) {
  EnvironmentMap env(testing::sun_map(20000), 1, rotation_axis_angle({1, 0, 0}, 20));
  const double reference = irradiance_quadrature(env);
  const int n = 100000;
  Rng rng(23);
  Estimate importance = estimate(n, [&] {
    EnvironmentSample s = env.sample(rng.uniform(), rng.uniform());
    if (!s.valid() || s.wi.z <= 0) return 0.0;
    return rec709_luminance(s.le) * s.wi.z / s.pdf;
  });
  Estimate uniform = estimate(n, [&] {
    glm::dvec3 w = sample_uniform_sphere(rng.uniform(), rng.uniform());
    return w.z > 0 ? 4 * kPi * rec709_luminance(env.radiance(w)) * w.z : 0.0;
  });
  EXPECT_NEAR(importance.mean, reference, 4 * importance.sigma);
  EXPECT_NEAR(uniform.mean, reference, 4 * uniform.sigma);
  double ratio = (uniform.sigma * uniform.sigma) / (importance.sigma * importance.sigma);
  ::testing::Test::RecordProperty("variance_ratio_uniform_over_importance", std::to_string(ratio));
  std::cout << "[ environment ] irradiance " << reference << ": importance " << importance.mean
            << " ± " << importance.sigma << ", uniform " << uniform.mean << " ± " << uniform.sigma
            << ", variance ratio " << ratio << "\n";
  EXPECT_GT(ratio, 10);
}

}  // namespace
}  // namespace raylane
