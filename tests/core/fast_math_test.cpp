#include "raylane/core/fast_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace raylane {
namespace {

constexpr long double kPiL = 3.141592653589793238462643383279502884L;

// The bound stated in fast_math.h; dropping the polynomials' last term (or any term) or
// rounding the reduction differently exceeds it by an order of magnitude.
constexpr double kSinCosBound = 3e-16;

void expect_sincos_close(double u) {
  SinCos sc = sincos_2pi(u);
  long double a = 2 * kPiL * (long double)u;
  EXPECT_LE(std::abs((long double)sc.sin - sinl(a)), kSinCosBound) << "u = " << u;
  EXPECT_LE(std::abs((long double)sc.cos - cosl(a)), kSinCosBound) << "u = " << u;
}

TEST(SinCos2Pi, WithinItsBoundOnAMillionTurns) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < (1 << 20); ++i)
    expect_sincos_close(double(rng() >> 11) * 0x1p-53);
}

TEST(SinCos2Pi, ExactWhereTheQuadrantsMeet) {
  for (int q = 0; q <= 8; ++q) {
    double u = q / 8.0;
    expect_sincos_close(u);
    expect_sincos_close(std::nextafter(u, 0.0));
    expect_sincos_close(std::nextafter(u, 1.0));
  }
  EXPECT_EQ(sincos_2pi(0).sin, 0.0);
  EXPECT_EQ(sincos_2pi(0).cos, 1.0);
  EXPECT_EQ(sincos_2pi(0.25).sin, 1.0);
  EXPECT_EQ(sincos_2pi(0.5).cos, -1.0);
  expect_sincos_close(0x1p-60);
}

}  // namespace
}  // namespace raylane
