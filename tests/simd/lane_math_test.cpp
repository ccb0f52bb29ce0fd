// The float lane transcendentals (simd/lane_math.h) against double libm, at the bounds the
// header states. Instantiated for SSE4.2 (every test binary's baseline); the kernels use the
// same templates at every width, and tests/render/shade_lanes_test.cpp runs them at the
// widths this CPU has.
#include "raylane/simd/lane_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace raylane {
namespace {

using A = xsimd::sse4_2;
using F = simd::Floats<A>;
constexpr int kW = simd::kWidth<A>;
constexpr double kUlp = 0x1p-24;

// Applies a lane function to xs, W at a time.
template <class Fn>
std::vector<float> lanes(const std::vector<float>& xs, Fn fn) {
  std::vector<float> out(xs.size());
  for (std::size_t i = 0; i + kW <= xs.size(); i += kW)
    simd::store<A>(out.data() + i, fn(simd::load<A>(xs.data() + i)));
  return out;
}

std::vector<float> uniform_floats(std::size_t n, float lo, float hi, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> d(lo, hi);
  std::vector<float> xs(n);
  for (float& x : xs)
    x = d(rng);
  return xs;
}

TEST(LaneMath, SinCos2PiWithinThreeUlpsAbsolute) {
  std::vector<float> u = uniform_floats(1 << 18, 0.0f, 1.0f, 1);
  for (int q = 0; q <= 8; ++q) {  // every octant edge and its float neighbours
    float e = float(q) / 8;
    u.insert(u.end(), {e, std::nextafter(e, 0.0f), std::nextafter(e, 1.0f), 0.0f});
  }
  while (u.size() % kW)
    u.push_back(0.5f);
  auto s = lanes(u, [](F x) { return simd::sincos_2pi<A>(x).sin; });
  auto c = lanes(u, [](F x) { return simd::sincos_2pi<A>(x).cos; });
  double worst = 0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    long double a = 2 * 3.141592653589793238462643383279502884L * (long double)u[i];
    worst = std::max(
        {worst, double(std::abs(s[i] - std::sin(a))), double(std::abs(c[i] - std::cos(a)))});
  }
  EXPECT_LE(worst, 3 * kUlp);
  EXPECT_GT(worst, 0.1 * kUlp);  // float after all: the test can see an error
}

TEST(LaneMath, Log2WithinFourAndAHalfUlpsRelative) {
  std::vector<float> x = uniform_floats(1 << 18, 0.0f, 1.0f, 2);
  std::vector<float> tiny = uniform_floats(1 << 12, 1e-37f, 1e-30f, 3);
  x.insert(x.end(), tiny.begin(), tiny.end());
  x.insert(x.end(), {1.0f, 0.5f, 0x1p-126f, std::nextafter(1.0f, 0.0f)});
  for (float& v : x)
    if (v < 0x1p-126f) v = 0x1p-126f;
  while (x.size() % kW)
    x.push_back(1.0f);
  auto l = lanes(x, [](F v) { return simd::log2<A>(v); });
  for (std::size_t i = 0; i < x.size(); ++i) {
    double exact = std::log2(double(x[i]));
    ASSERT_LE(std::abs(l[i] - exact), 4.5 * kUlp * std::abs(exact)) << x[i];
    if (x[i] == 1.0f) {
      EXPECT_EQ(l[i], 0.0f);  // exactly: cos^α of a head-on microfacet is 1
    }
  }
}

TEST(LaneMath, Exp2WithinTwoUlpsRelative) {
  std::vector<float> t = uniform_floats(1 << 18, -126.0f, 127.0f, 4);
  std::vector<float> near0 = uniform_floats(1 << 12, -1.0f, 1.0f, 5);
  t.insert(t.end(), near0.begin(), near0.end());
  t.insert(t.end(), {0.0f, -0.5f, 0.5f, -126.0f, 127.0f, -1.5f});
  while (t.size() % kW)
    t.push_back(0.0f);
  auto e = lanes(t, [](F v) { return simd::exp2<A>(v); });
  for (std::size_t i = 0; i < t.size(); ++i) {
    double exact = std::exp2(double(t[i]));
    ASSERT_LE(std::abs(e[i] - exact), 2 * kUlp * exact) << t[i];
  }
}

// The Phong lobe's uses: cos^α θm with α up to 4096 and the warp's u^(1/(α+1)).
TEST(LaneMath, PowWithinItsBound) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_real_distribution<float> alpha(0.0f, 4096.0f);
  constexpr int kN = 1 << 18;
  std::vector<float> x(kN), y(kN), got(kN);
  for (int i = 0; i < kN; ++i) {
    float a = alpha(rng);
    x[i] = i % 3 == 0 ? 1 - unit(rng) * 1e-3f : unit(rng);  // many near 1: a narrow lobe's peak
    y[i] = i % 2 ? a : 1 / (a + 1);
  }
  x[0] = 0, y[0] = 2;  // 0^y = 0
  x[1] = 0, y[1] = 0;  // 0^0 = 1
  x[2] = 1, y[2] = 4096;
  for (int i = 0; i < kN; i += kW)
    simd::store<A>(got.data() + i,
                   simd::pow_unit<A>(simd::load<A>(x.data() + i), simd::load<A>(y.data() + i)));
  EXPECT_EQ(got[0], 0.0f);
  EXPECT_EQ(got[1], 1.0f);
  EXPECT_EQ(got[2], 1.0f);
  double worst_excess = 0;
  for (int i = 3; i < kN; ++i) {
    double exact = std::pow(double(x[i]), double(y[i]));
    if (exact < 0x1p-126) continue;  // flushed: below every float the lobe uses
    double t = std::abs(double(y[i]) * std::log2(double(x[i])));
    double bound = (3 + 3.5 * t) * kUlp * exact;
    ASSERT_LE(std::abs(got[i] - exact), bound) << x[i] << "^" << y[i];
    worst_excess = std::max(worst_excess, std::abs(got[i] - exact) / (kUlp * exact) - 3);
  }
  EXPECT_GT(worst_excess, -3);  // some error at all: the comparison is live
}

}  // namespace
}  // namespace raylane
