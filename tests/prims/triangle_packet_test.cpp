// prims/triangle_packet.h: the watertight test's sign rule on its edge functions, as a min and
// a max, against the rule as Woop et al. (2013, §3) state it (reject when some edge function
// is below 0 and some above), on every combination of the values where the two could part:
// signed zeros, subnormals, infinities, the largest floats. Instantiated for SSE4.2 (every test
// binary's baseline); the tracer uses the same template at every width, and the packet tests
// (tests/trace/packet_test.cpp) hold its answers against the reference at every ISA.
#include "raylane/prims/triangle_packet.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <limits>
#include <vector>

namespace raylane {
namespace {

using A = xsimd::sse4_2;
using F = simd::Floats<A>;

// The rule as stated, one value at a time.
bool mixed_by_definition(float u, float v, float w) {
  bool negative = u < 0.0f || v < 0.0f || w < 0.0f;
  bool positive = u > 0.0f || v > 0.0f || w > 0.0f;
  return negative && positive;
}

TEST(TrianglePacket, MixedSignsIsTheSixCompareRuleOnEveryNumber) {
  const float inf = std::numeric_limits<float>::infinity();
  const float sub = std::numeric_limits<float>::denorm_min();
  std::vector<float> values;
  for (float x : {0.0f, sub, FLT_MIN, 1e-30f, 1.0f, 3.5e5f, FLT_MAX, inf})
    values.push_back(x), values.push_back(-x);  // -0.0f included: it is neither < 0 nor > 0
  constexpr int W = simd::kWidth<A>;
  int checked = 0, mixed = 0;
  // Every (u, v, w) triple, W of them per call, each lane a different triple.
  std::vector<std::array<float, 3>> triples;
  for (float u : values)
    for (float v : values)
      for (float w : values)
        triples.push_back({u, v, w});
  for (std::size_t i = 0; i < triples.size(); i += W) {
    alignas(64) float col[3][W];
    for (int k = 0; k < W; ++k)
      for (int c = 0; c < 3; ++c)
        col[c][k] = triples[std::min(i + std::size_t(k), triples.size() - 1)][c];
    uint32_t got = simd::bits<A>(
        mixed_signs<A>(simd::load<A>(col[0]), simd::load<A>(col[1]), simd::load<A>(col[2])));
    for (int k = 0; k < W && i + std::size_t(k) < triples.size(); ++k) {
      bool want = mixed_by_definition(col[0][k], col[1][k], col[2][k]);
      EXPECT_EQ(((got >> k) & 1u) != 0, want) << col[0][k] << " " << col[1][k] << " " << col[2][k];
      ++checked;
      mixed += want;
    }
  }
  EXPECT_EQ(checked, 16 * 16 * 16);
  EXPECT_GT(mixed, 0);  // both answers were asked for
  EXPECT_LT(mixed, checked);
}

}  // namespace
}  // namespace raylane
