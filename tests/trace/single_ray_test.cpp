// trace/single_ray.h: a ray set up in scalar code gets the frame, reciprocals and slab sides the
// packet set-up (RayShear, SlabSides) gives it, bit for bit, so single rays and packets run the
// kernels on the same numbers. Instantiated for SSE4.2 (every test binary's baseline); the
// tracer uses the same templates at every width (tests/trace/packet_test.cpp).
#include "raylane/trace/single_ray.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace raylane {
namespace {

using A = xsimd::sse4_2;
using F = simd::Floats<A>;

bool same_bits(float a, float b) {
  return std::memcmp(&a, &b, sizeof(float)) == 0;
}

// Directions that reach every branch of the frame: random ones, ties between |d| components
// (the lowest axis wins), signed zeros and negative largest components (x and y swap).
std::vector<std::array<float, 3>> directions() {
  std::vector<std::array<float, 3>> ds;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 20000; ++i)
    ds.push_back({u(rng), u(rng), u(rng)});
  for (float a : {1.0f, -1.0f, 0.5f})
    for (float b : {1.0f, -1.0f, 0.0f, -0.0f, 0.25f})
      for (float c : {1.0f, -1.0f, 0.0f, -0.0f})
        ds.push_back({a, b, c}), ds.push_back({b, a, c}), ds.push_back({c, b, a});
  return ds;
}

TEST(SingleRay, FrameMatchesThePacketSetUpBitForBit) {
  int checked = 0;
  for (const auto& d : directions()) {
    RayScalars r{{0.5f, -2.0f, 3.0f}, {d[0], d[1], d[2]}, {}, 0.0f, 10.0f};
    for (int k = 0; k < 3; ++k)
      r.inv[k] = 1.0f / r.d[k];
    if (!single_ray_valid(r)) continue;
    RayPacket<A> one = broadcast_ray<A>(r);
    F inv_x(1.0f / d[0]), inv_y(1.0f / d[1]), inv_z(1.0f / d[2]);
    simd::Mask<A> all = simd::first_lanes<A>(simd::kWidth<A>);
    RayShear<A> packet;
    packet.set(F(d[0]), F(d[1]), F(d[2]), all);
    SlabSides<A> sides;
    sides.set(inv_x, inv_y, inv_z, all);
    ASSERT_TRUE(packet.uniform);
    EXPECT_EQ(one.shear.kx, packet.kx) << d[0] << " " << d[1] << " " << d[2];
    EXPECT_EQ(one.shear.ky, packet.ky) << d[0] << " " << d[1] << " " << d[2];
    EXPECT_EQ(one.shear.kz, packet.kz) << d[0] << " " << d[1] << " " << d[2];
    EXPECT_TRUE(same_bits(one.shear.sx.get(0), packet.sx.get(0)));
    EXPECT_TRUE(same_bits(one.shear.sy.get(0), packet.sy.get(0)));
    EXPECT_TRUE(same_bits(one.shear.sz.get(0), packet.sz.get(0)));
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(simd::bits<A>(one.shear.x_is[k]), simd::bits<A>(packet.x_is[k]));
      EXPECT_EQ(simd::bits<A>(one.shear.y_is[k]), simd::bits<A>(packet.y_is[k]));
      EXPECT_EQ(simd::bits<A>(one.shear.z_is[k]), simd::bits<A>(packet.z_is[k]));
      EXPECT_EQ(one.sides.near_hi[k], sides.near_hi[k]);
      EXPECT_EQ(one.sides.hi_first_bits[k], sides.hi_first_bits[k]);
    }
    ++checked;
  }
  EXPECT_GT(checked, 20000);
}

// The packet path's validity test, lane for lane (docs/hard-cases.md N1).
TEST(SingleRay, InvalidRaysAreRefused) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::nanf("");
  auto ray = [](std::array<float, 3> o, std::array<float, 3> d, float tmin, float tmax) {
    return RayScalars{{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, {}, tmin, tmax};
  };
  EXPECT_TRUE(single_ray_valid(ray({0, 0, 0}, {0, 0, -1}, 0, inf)));
  EXPECT_FALSE(single_ray_valid(ray({0, 0, 0}, {0, 0, 0}, 0, inf)));
  EXPECT_FALSE(single_ray_valid(ray({0, nan, 0}, {0, 0, 1}, 0, inf)));
  EXPECT_FALSE(single_ray_valid(ray({0, 0, 0}, {inf, 0, 1}, 0, inf)));
  EXPECT_FALSE(single_ray_valid(ray({0, 0, 0}, {0, 0, 1}, 2, 1)));
  EXPECT_FALSE(single_ray_valid(ray({0, 0, 0}, {0, 0, 1}, nan, 1)));
}

}  // namespace
}  // namespace raylane
