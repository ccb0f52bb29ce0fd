#include "raylane/core/float_util.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>
#include <random>

namespace raylane {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// docs/hard-cases.md N4: the neighbours of special values.
TEST(NextFloat, SpecialValues) {
  EXPECT_EQ(next_float_up(FLT_MAX), kInf);
  EXPECT_EQ(next_float_up(kInf), kInf);
  EXPECT_EQ(next_float_down(-FLT_MAX), -kInf);
  EXPECT_EQ(next_float_down(-kInf), -kInf);
  EXPECT_EQ(next_float_up(-kInf), -FLT_MAX);
  EXPECT_EQ(next_float_down(kInf), FLT_MAX);
  EXPECT_EQ(next_float_up(0.0f), std::numeric_limits<float>::denorm_min());
  EXPECT_EQ(next_float_up(-0.0f), std::numeric_limits<float>::denorm_min());
  EXPECT_EQ(next_float_down(0.0f), -std::numeric_limits<float>::denorm_min());
  EXPECT_EQ(next_float_down(std::numeric_limits<float>::denorm_min()), 0.0f);
  EXPECT_TRUE(std::isnan(next_float_up(std::nanf(""))));
  EXPECT_TRUE(std::isnan(next_float_down(std::nanf(""))));
}

TEST(NextFloat, AgreesWithNextafterOnRandomFloats) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<uint32_t> bits;
  int checked = 0;
  for (int i = 0; i < 1000000; ++i) {
    float v = std::bit_cast<float>(bits(rng));
    if (std::isnan(v)) continue;
    ASSERT_EQ(next_float_up(v), std::nextafter(v, kInf)) << v;
    ASSERT_EQ(next_float_down(v), std::nextafter(v, -kInf)) << v;
    ASSERT_FALSE(std::isnan(next_float_up(v)));
    ++checked;
  }
  EXPECT_GT(checked, 990000);
}

TEST(UlpDistance, CountsFloatsAcrossZero) {
  EXPECT_EQ(ulp_distance(1.0f, 1.0f), 0u);
  EXPECT_EQ(ulp_distance(1.0f, std::nextafter(1.0f, 2.0f)), 1u);
  EXPECT_EQ(ulp_distance(0.0f, -0.0f), 0u);
  float tiny = std::numeric_limits<float>::denorm_min();
  EXPECT_EQ(ulp_distance(-tiny, tiny), 2u);
  EXPECT_EQ(ulp_distance(std::nanf(""), 1.0f), std::numeric_limits<uint64_t>::max());
}

int sign(double v) {
  return (v > 0) - (v < 0);
}

TEST(DifferenceOfProducts, HasTheExactSignAndIsAccurate) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1e3f, 1e3f);
  for (int i = 0; i < 100000; ++i) {
    float a = u(rng), b = u(rng), c = u(rng), d = u(rng);
    float x = difference_of_products(a, b, c, d);
    double exact = double(a) * b - double(c) * d;  // exact: 24+24 bit products fit in double
    // Kahan's algorithm is within 1.5 ulp (Jeannerod, Louvet, Muller 2013).
    ASSERT_LE(std::abs(x - exact), 1.5 * std::abs(exact) * 0x1p-23 + 1e-30) << a << b << c << d;
    ASSERT_EQ(sign(x), sign(exact));
    ASSERT_EQ(sign(difference_of_products(c, d, a, b)), -sign(exact));
  }
  // Exactly equal products give exactly 0, in both orders.
  EXPECT_EQ(difference_of_products(3.0f, 0.1f, 0.1f, 3.0f), 0.0f);
}

TEST(Gamma, MatchesDefinition) {
  EXPECT_DOUBLE_EQ(gamma_float(1), 0x1p-24 / (1 - 0x1p-24));
  EXPECT_GT(gamma_float(3), 3 * 0x1p-24);
}

}  // namespace
}  // namespace raylane

namespace raylane {
namespace {

// The double steps are std::nextafter toward ±inf, on special values and on random bit
// patterns of every exponent.
TEST(NextDouble, IsNextafterTowardInfinity) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> values = {0.0,     -0.0,     1.0,
                                -1.0,    DBL_MAX,  -DBL_MAX,
                                DBL_MIN, -DBL_MIN, std::numeric_limits<double>::denorm_min(),
                                inf,     -inf};
  std::mt19937_64 rng(11);
  for (int i = 0; i < 100000; ++i) {
    double v = std::bit_cast<double>(rng());
    if (!std::isnan(v)) values.push_back(v);
  }
  for (double v : values) {
    EXPECT_EQ(std::bit_cast<uint64_t>(next_double_up(v)),
              std::bit_cast<uint64_t>(std::nextafter(v, inf)))
        << v;
    EXPECT_EQ(std::bit_cast<uint64_t>(next_double_down(v)),
              std::bit_cast<uint64_t>(std::nextafter(v, -inf)))
        << v;
  }
  EXPECT_TRUE(std::isnan(next_double_up(std::nan(""))));
}

}  // namespace
}  // namespace raylane
