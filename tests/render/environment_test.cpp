// The environment light's image side (render/lights/environment.h): the equirectangular mapping and
// its bilinear lookup, the piecewise-constant distributions, the sampling density's support and
// shape, the power, and black or broken maps. Sampling against its density is in
// environment_sampling_test.cpp.
#include "raylane/render/lights/environment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "env_maps.h"
#include "raylane/render/samplers/rng.h"

namespace raylane {
namespace {

using testing::direction_of;
using testing::make_image;

constexpr double kBelowOne = 0x1.fffffffffffffp-1;

void expect_rgb(const glm::dvec3& got, const glm::dvec3& want, double tol = 1e-12) {
  EXPECT_NEAR(got.x, want.x, tol * (1 + std::abs(want.x)));
  EXPECT_NEAR(got.y, want.y, tol * (1 + std::abs(want.y)));
  EXPECT_NEAR(got.z, want.z, tol * (1 + std::abs(want.z)));
}

// 4×2, every texel its own colour: texel (x, y) = (x + 1, 10·(y + 1), x + 4y).
Image four_by_two() {
  return make_image(4, 2, [](uint32_t x, uint32_t y) {
    return glm::vec3(float(x + 1), float(10 * (y + 1)), float(x + 4 * y));
  });
}

TEST(EnvironmentMapping, TopRowLooksUpBottomRowLooksDown) {
  Image img = make_image(8, 4, [](uint32_t x, uint32_t y) {
    if (y == 0) return glm::vec3(1, 2, 3);
    if (y == 3) return glm::vec3(4, 5, 6);
    return glm::vec3(float(x), 7, 8);
  });
  EnvironmentMap env(img, 2.5, glm::dmat3(1.0));
  expect_rgb(env.radiance({0, 0, 1}), glm::dvec3(2.5, 5, 7.5));
  expect_rgb(env.radiance({0, 0, -1}), glm::dvec3(10, 12.5, 15));
  expect_rgb(env.radiance({0, 0, 3}), glm::dvec3(2.5, 5, 7.5));  // the length does not matter
}

TEST(EnvironmentMapping, TexelCentresReadTheirTexel) {
  Image img = four_by_two();
  EnvironmentMap env(img, 1, glm::dmat3(1.0));
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 4; ++x) {
      SCOPED_TRACE(::testing::Message() << "texel " << x << "," << y);
      expect_rgb(env.radiance(direction_of((x + 0.5) / 4, (y + 0.5) / 2)),
                 glm::dvec3(img.at(x, y)));
    }
  // φ = π/4, θ = π/4: column 0, top row. (1, 0, 0) is φ = 0, θ = π/2: on the seam between the
  // last and first columns and between the rows, so the mean of those four texels.
  expect_rgb(env.radiance({1, 1, std::sqrt(2.0)}), glm::dvec3(1, 10, 0));
  glm::dvec3 seam = (glm::dvec3(img.at(3, 0)) + glm::dvec3(img.at(0, 0)) +
                     glm::dvec3(img.at(3, 1)) + glm::dvec3(img.at(0, 1))) /
                    4.0;
  expect_rgb(env.radiance({1, 0, 0}), seam);
}

TEST(EnvironmentMapping, UWrapsAcrossTheSeam) {
  Image img = four_by_two();
  EnvironmentMap env(img, 1, glm::dmat3(1.0));
  const double v = 0.25;  // the top row's centre
  glm::dvec3 last(img.at(3, 0)), first(img.at(0, 0));
  // A quarter texel before the seam (φ near 2π): 3/4 of the last column, 1/4 of the first.
  expect_rgb(env.radiance(direction_of(1 - 0.25 / 4, v)), last * 0.75 + first * 0.25);
  // A quarter texel after it (φ near 0): the other way round.
  expect_rgb(env.radiance(direction_of(0.25 / 4, v)), last * 0.25 + first * 0.75);
  // Just either side of φ = 0 the lookup is continuous.
  expect_rgb(env.radiance(direction_of(kBelowOne, v)), env.radiance(direction_of(0, v)), 1e-9);
  // Clamped in v: above the first row's centre the lookup stays on that row.
  expect_rgb(env.radiance(direction_of(0.375, 0.1)), glm::dvec3(img.at(1, 0)));
}

TEST(EnvironmentMapping, RotationTurnsTheImageIntoTheWorld) {
  Image img = make_image(8, 4, [](uint32_t x, uint32_t y) {
    return y == 0 ? glm::vec3(9, 9, 9) : glm::vec3(float(x), float(y), 1);
  });
  glm::dmat3 r = rotation_axis_angle({1, 0, 0}, 90);
  EnvironmentMap turned(img, 1, r), plain(img, 1, glm::dmat3(1.0));
  glm::dvec3 zenith = r * glm::dvec3(0, 0, 1);
  EXPECT_NEAR(zenith.y, -1, 1e-15);  // 90° about +x takes +z to −y
  expect_rgb(turned.radiance(zenith), glm::dvec3(9, 9, 9));
  EXPECT_NE(turned.radiance({0, 0, 1}).x, 9);
  // Everywhere: the rotated map at R·d reads what the plain map reads at d.
  Rng rng(3);
  for (int i = 0; i < 1000; ++i) {
    glm::dvec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
    expect_rgb(turned.radiance(r * d), plain.radiance(d), 1e-9);
  }
}

TEST(PiecewiseConstant1D, InvertsTheCdf) {
  PiecewiseConstant1D d({1, 0, 3, 0});  // CDF 0, 1/4, 1/4, 1, 1
  EXPECT_EQ(d.size(), 4u);
  EXPECT_DOUBLE_EQ(d.integral(), 1.0);
  double pdf = 0;
  uint32_t cell = 9;
  EXPECT_DOUBLE_EQ(d.sample_continuous(0.1, &pdf, &cell), 0.1);
  EXPECT_EQ(cell, 0u);
  EXPECT_DOUBLE_EQ(pdf, 1.0);
  EXPECT_DOUBLE_EQ(d.sample_continuous(0.25, &pdf, &cell), 0.5);  // skips the empty cell 1
  EXPECT_EQ(cell, 2u);
  EXPECT_DOUBLE_EQ(pdf, 3.0);
  EXPECT_DOUBLE_EQ(d.sample_continuous(0.625, &pdf, &cell), 0.625);
  EXPECT_LT(d.sample_continuous(kBelowOne, &pdf, &cell), 0.75);  // never the empty cell 3
  EXPECT_EQ(cell, 2u);
  EXPECT_DOUBLE_EQ(d.sample_continuous(0, &pdf, &cell), 0.0);
  EXPECT_EQ(cell, 0u);
  EXPECT_DOUBLE_EQ(d.pdf(0.3), 0.0);
  EXPECT_DOUBLE_EQ(d.pdf(0.6), 3.0);
  EXPECT_DOUBLE_EQ(d.pdf(1.0), 0.0);
}

TEST(PiecewiseConstant1D, ZeroCellsAreNeverSampledAndThePdfSumsToOne) {
  PiecewiseConstant1D d({0, 0, 2, 0, 1e-300, 5, 0, 0});
  double sum = 0;
  for (uint32_t i = 0; i < d.size(); ++i)
    sum += d.pdf_of_cell(i) / d.size();
  EXPECT_NEAR(sum, 1, 1e-15);
  for (int k = 0; k <= 100000; ++k) {
    double u = k < 100000 ? k / 100000.0 : kBelowOne, pdf = 0;
    uint32_t cell = 0;
    double x = d.sample_continuous(u, &pdf, &cell);
    ASSERT_GT(d.pdf_of_cell(cell), 0) << "u = " << u;
    ASSERT_GT(pdf, 0);
    ASSERT_TRUE(x >= cell / 8.0 && x <= (cell + 1) / 8.0 && x < 1) << x;
  }
}

// The fixed-point CDF gives every cell of weight > 0 a step of at least one unit, however small
// its share, and still ends at exactly one: the densities of the cells sum to exactly 1, a tiny
// cell is sampled at its unit (where it shows light that MIS must be able to reach), and its
// density is the step it has. Tiny cells first and last (where the forward pass's lifts pile up
// against the end).
TEST(PiecewiseConstant1D, EveryLitCellHasAUnitAndTheDensitiesSumToOne) {
  for (int layout = 0; layout < 2; ++layout) {
    std::vector<double> f(2000, 1e-30);
    f[layout == 0 ? 1999 : 0] = 1;
    PiecewiseConstant1D d(f);
    const double n = double(d.size());
    double sum = 0;
    for (uint32_t i = 0; i < d.size(); ++i) {
      ASSERT_GE(d.pdf_of_cell(i), n / PiecewiseConstant1D::kUnits) << "cell " << i;
      sum += d.pdf_of_cell(i) / n;
    }
    EXPECT_EQ(sum, 1.0);  // steps in units of 2^-31 sum exactly in double
    // The first unit of each tiny cell's step lands in that cell.
    double unit = 1.0 / PiecewiseConstant1D::kUnits, at = 0;
    for (uint32_t i = 0; i < d.size(); ++i) {
      uint32_t cell = 0;
      double pdf = 0;
      d.sample_continuous(at, &pdf, &cell);
      ASSERT_EQ(cell, i) << "layout " << layout;
      ASSERT_EQ(pdf, d.pdf_of_cell(i));
      at += d.pdf_of_cell(i) / n;
      if (f[i] < 1) {
        ASSERT_LT(d.pdf_of_cell(i) / n, 1.5 * unit);  // one unit: no more than rounding gives
      }
    }
  }
}

// A search takes as many select steps as the table's longest guided span needs. Empty cells
// at the end (the marginal of a map whose lower half is black) lie past the last lit cell and
// must not make the last span long: eight lit cells then a thousand empty ones search as eight
// cells do, and the last unit still lands in the last lit cell.
TEST(PiecewiseConstant1D, EmptyCellsAtTheEndDoNotLengthenTheSearch) {
  std::vector<double> f(1008, 0.0);
  for (int i = 0; i < 8; ++i)
    f[std::size_t(i)] = 1 + i;
  PiecewiseConstant1D d(f);
  EXPECT_LE(d.search_steps(), 3u);  // a span of at most 7 cells: steps 4, 2, 1
  uint32_t cell = 0;
  double pdf = 0;
  d.sample_continuous(0x1.fffffffffffffp-1, &pdf, &cell);
  EXPECT_EQ(cell, 7u);
  EXPECT_GT(pdf, 0);
  // The same cells in front of the empty ones search as long as the lit cells need.
  std::reverse(f.begin(), f.end());
  EXPECT_LE(PiecewiseConstant1D(f).search_steps(), 3u);
}

// The environment's sampling tables take 5 bytes a pixel (docs/scene-language.md, "Image
// memory": a CDF entry and a quarter of a guide entry) and a few words a row, besides the
// texels the scene holds.
TEST(PiecewiseConstant2D, TablesTakeFiveBytesAPixel) {
  const uint32_t w = 256, h = 64;
  EnvironmentMap env(
      testing::make_image(
          w, h, [](uint32_t x, uint32_t y) { return glm::vec3(1 + x % 7, 1 + y % 3, 1); }),
      1, glm::dmat3(1.0));
  const std::size_t tables = env.bytes() - sizeof(EnvironmentMap) - env.texels().bytes();
  EXPECT_GE(tables, std::size_t(5) * w * h);
  EXPECT_LE(tables, std::size_t(5) * w * h + 128 * std::size_t(h) + 4096);
}

TEST(PiecewiseConstant1D, AllZeroSamplesNothing) {
  PiecewiseConstant1D d({0, 0, 0});
  double pdf = 1;
  double x = d.sample_continuous(0.5, &pdf);
  EXPECT_EQ(pdf, 0);
  EXPECT_TRUE(std::isfinite(x));
  EXPECT_EQ(d.pdf(0.5), 0);
  EXPECT_EQ(d.integral(), 0);
}

TEST(PiecewiseConstant2D, SamplesRowThenColumn) {
  // Rows {1, 2, 0} and {0, 0, 3}: Σf = 6 over 6 cells, so ∫∫f = 1 and the density is f.
  PiecewiseConstant2D d({1, 2, 0, 0, 0, 3}, 3, 2);
  // The row's CDF ends at 1/3 of 2^31 units, rounded: the density and the point within the cell
  // move by up to half a unit of the 2^31 over the cell's share.
  const double off = 3 * 0.5 / PiecewiseConstant1D::kUnits;
  EXPECT_DOUBLE_EQ(d.integral(), 1.0);
  // u2 = 1/4: the first row (marginal CDF 0, 1/2, 1), halfway: v = 1/4. u1 = 1/2: the row's
  // CDF is 0, 1/3, 1, 1, so cell 1, a quarter in: u = 1.25/3.
  auto s = d.sample(0.5, 0.25);
  EXPECT_NEAR(s.v, 0.25, 1e-15);
  EXPECT_NEAR(s.u, 1.25 / 3, off);
  EXPECT_EQ(s.cell_u, 1u);
  EXPECT_EQ(s.cell_v, 0u);
  EXPECT_NEAR(s.pdf, 2.0, 2 * off);
  EXPECT_EQ(d.pdf(s.u, s.v), s.pdf);
  auto t = d.sample(0.1, 0.9);
  EXPECT_EQ(t.cell_u, 2u);  // the second row's only non-zero cell
  EXPECT_EQ(t.cell_v, 1u);
  EXPECT_DOUBLE_EQ(t.pdf, 3.0);
  EXPECT_EQ(d.pdf(0.1, 0.9), 0.0);
  double sum = 0;
  for (int v = 0; v < 2; ++v)
    for (int u = 0; u < 3; ++u)
      sum += d.pdf((u + 0.5) / 3, (v + 0.5) / 2) / 6;
  EXPECT_NEAR(sum, 1, 1e-15);
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200; ++j) {
      auto r = d.sample(i < 200 ? i / 200.0 : kBelowOne, j < 200 ? j / 200.0 : kBelowOne);
      ASSERT_GT(r.pdf, 0);
      ASSERT_GT(d.pdf(r.u, r.v), 0) << r.u << " " << r.v;
    }
}

// A constant map's density is uniform over the sphere, up to the row-centre sin θ (O(1/h²)):
// the sin θ factor of the weights is what makes it so.
TEST(EnvironmentSampling, ConstantMapIsSampledUniformly) {
  EnvironmentMap env(make_image(32, 16, [](uint32_t, uint32_t) { return glm::vec3(1, 1, 1); }), 1,
                     glm::dmat3(1.0));
  for (int y = 0; y < 16; ++y)
    EXPECT_NEAR(env.pdf(direction_of(0.3, (y + 0.5) / 16)) * 4 * kPi, 1, 2e-3) << "row " << y;
}

// MIS needs the density > 0 wherever the radiance is: one lit texel in a black map lights the
// cells around it through the bilinear lookup.
TEST(EnvironmentSampling, DensityCoversTheBilinearSpread) {
  Image img = make_image(16, 8, [](uint32_t x, uint32_t y) {
    return x == 0 && y == 3 ? glm::vec3(0, 0, 1) : glm::vec3(0, 0, 0);
  });
  EnvironmentMap env(img, 1, rotation_axis_angle({0, 1, 0}, 30));
  int lit = 0;
  for (int i = 0; i < 640; ++i)
    for (int j = 0; j < 320; ++j) {
      glm::dvec3 d = env.rotation() * direction_of((i + 0.5) / 640, (j + 0.5) / 320);
      if (env.radiance(d).z == 0) continue;
      ++lit;
      ASSERT_GT(env.pdf(d), 0) << "u = " << (i + 0.5) / 640 << ", v = " << (j + 0.5) / 320;
    }
  EXPECT_EQ(lit, 80 * 80) << "the tent covers 2×2 texels' worth of points";
}

TEST(EnvironmentPower, IsTheBilinearMapsFluxThroughTheSceneDisc) {
  Image grey = make_image(16, 8, [](uint32_t, uint32_t) { return glm::vec3(2, 2, 2); });
  EnvironmentMap constant(grey, 1.5, glm::dmat3(1.0));
  // Φ = π r² · 4π · s · lum, lum(2, 2, 2) = 2.
  EXPECT_NEAR(constant.power_estimate(3), kPi * 9 * 4 * kPi * 1.5 * 2, 1e-10);
  EXPECT_NEAR(constant.average_luminance(), 3, 1e-12);
  // A smooth map against a midpoint quadrature of its lookup (sub-cells meet at texel centres).
  EnvironmentMap env(testing::gradient_map(), 0.5, rotation_axis_angle({1, 1, 0}, 40));
  const int nu = 48 * 16, nv = 24 * 16;
  double sum = 0;
  for (int j = 0; j < nv; ++j) {
    double v = (j + 0.5) / nv, sin_theta = std::sin(kPi * v);
    for (int i = 0; i < nu; ++i)
      sum += rec709_luminance(env.radiance_uv((i + 0.5) / nu, v)) * sin_theta;
  }
  double integral = sum * 2 * kPi * kPi / (double(nu) * nv);
  EXPECT_NEAR(env.power_estimate(2) / (kPi * 4), integral, 1e-5 * integral);
}

TEST(EnvironmentBlack, SamplesNothingAndNeverNaN) {
  EnvironmentMap env(Image(8, 4), 1, rotation_axis_angle({0, 0, 1}, 10));
  EXPECT_FALSE(env.can_sample());
  EXPECT_EQ(env.power_estimate(10), 0);
  EXPECT_EQ(env.average_luminance(), 0);
  for (double u1 : {0.0, 0.5, kBelowOne, 1.0})
    for (double u2 : {0.0, 0.3, kBelowOne, 1.0}) {
      EnvironmentSample s = env.sample(u1, u2);
      EXPECT_FALSE(s.valid());
      EXPECT_EQ(s.pdf, 0);
      EXPECT_TRUE(is_finite(s.wi) && is_finite(s.le));
    }
  for (glm::dvec3 d :
       {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 0)}) {
    EXPECT_EQ(env.pdf(d), 0);
    EXPECT_EQ(env.radiance(d), glm::dvec3(0, 0, 0));
  }
}

TEST(EnvironmentBlack, BrokenInputsBecomeBlackOrZero) {
  Image bad(2, 1);
  bad.rgb = {-1, NAN, INFINITY, 1, 1, 1};
  EnvironmentMap sanitized(bad, 1, glm::dmat3(1.0));
  EXPECT_TRUE(is_finite(sanitized.radiance({1, 0, 0})));
  EXPECT_TRUE(sanitized.can_sample());
  EXPECT_FALSE(EnvironmentMap(Image(), 1, glm::dmat3(1.0)).can_sample());
  EXPECT_FALSE(EnvironmentMap(Image(4, 2), 1, glm::dmat3(1.0)).can_sample());
  Image lit = make_image(4, 2, [](uint32_t, uint32_t) { return glm::vec3(1, 1, 1); });
  EXPECT_FALSE(EnvironmentMap(lit, 0, glm::dmat3(1.0)).can_sample());
  EXPECT_FALSE(EnvironmentMap(lit, NAN, glm::dmat3(1.0)).can_sample());
  EXPECT_EQ(EnvironmentMap(lit, -1, glm::dmat3(1.0)).power_estimate(1), 0);
}

}  // namespace
}  // namespace raylane
