// The texel lookup written once over the number type (render/materials/texel_lookup.h): the double
// one over compact texels is the float image's bit for bit, the float one agrees with it to float
// precision, and the float lanes return what the scalar float lookup returns, lane by lane.
// Instantiated for SSE4.2 (every test binary's baseline), as tests/simd/lane_math_test.cpp is.
#include "raylane/render/materials/texel_lookup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "raylane/render/materials/texel_lanes.h"

namespace raylane {
namespace {

using A = xsimd::sse4_2;
constexpr int kW = simd::kWidth<A>;

// An image whose values are all halves, in a few decades, so that the texels are kHalf.
Image half_image(uint32_t w, uint32_t h) {
  Image img(w, h);
  for (std::size_t i = 0; i < img.rgb.size(); ++i)
    img.rgb[i] = half_to_float(uint16_t((i * 2654435761u) % 0x5000u));
  return img;
}

TexelImage srgb_texels(uint32_t w, uint32_t h) {
  std::vector<uint8_t> bytes(std::size_t(w) * h * 3);
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = uint8_t(i * 37 + 11);
  return srgb8_texels(w, h, bytes);
}

std::vector<std::pair<double, double>> coordinates(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> d(-3.0, 3.0);
  std::vector<std::pair<double, double>> uv;
  for (int i = 0; i < 4000; ++i)
    uv.emplace_back(d(rng), d(rng));
  // Texel centres, edges and seams.
  for (double c : {0.0, 0.5 / 7, 1.0 / 7, 0.5, 1.0 - 1e-12, 1.0})
    uv.emplace_back(c, 1 - c);
  return uv;
}

TEST(TexelLookup, DoubleOverTexelsIsTheFloatImagesBitForBit) {
  Image img = half_image(7, 5);
  TexelImage t = float_texels(img);
  ASSERT_EQ(t.format, TexelFormat::kHalf);
  for (auto [u, v] : coordinates(1)) {
    LinearRgb<double> a = texture_texel_lookup<double>(t, u, v);
    LinearRgb<double> b = texture_texel_lookup<double>(img, u, v);
    ASSERT_EQ(a.r, b.r) << u << " " << v;
    ASSERT_EQ(a.g, b.g);
    ASSERT_EQ(a.b, b.b);
    LinearRgb<double> e = environment_texel_lookup<double>(t, u, v);
    LinearRgb<double> f = environment_texel_lookup<double>(img, u, v);
    ASSERT_EQ(e.r, f.r) << u << " " << v;
  }
}

TEST(TexelLookup, TexelCentresAreTheTexelsAndTheEdgesWrapOrClamp) {
  TexelImage t = srgb_texels(4, 3);
  // Texture: v up, so v in the bottom third is the file's last row.
  LinearRgb<double> c = texture_texel_lookup<double>(t, 1.5 / 4, 0.5 / 3);
  EXPECT_EQ(c.r, t.at(1, 2).x);
  EXPECT_EQ(c.b, t.at(1, 2).z);
  // The u seam: halfway between the last and first columns.
  LinearRgb<double> seam = texture_texel_lookup<double>(t, 0.0, 0.5 / 3);
  EXPECT_DOUBLE_EQ(seam.g, 0.5 * (double(t.at(3, 2).y) + t.at(0, 2).y));
  // Environment: v down from the top, clamped above the first row's centre.
  LinearRgb<double> top = environment_texel_lookup<double>(t, 2.5 / 4, 0.0);
  EXPECT_EQ(top.r, t.at(2, 0).x);
  // Non-finite coordinates are black.
  EXPECT_EQ(texture_texel_lookup<double>(t, NAN, 0.5).r, 0.0);
  EXPECT_EQ(environment_texel_lookup<double>(t, 0.5, INFINITY).g, 0.0);
}

TEST(TexelLookup, FloatAgreesWithDoubleToFloatPrecision) {
  TexelImage t = srgb_texels(9, 6);
  for (auto [u, v] : coordinates(2)) {
    float uf = float(u), vf = float(v);
    LinearRgb<double> d = texture_texel_lookup<double>(t, double(uf), double(vf));
    LinearRgb<float> f = texture_texel_lookup<float>(t, uf, vf);
    // Weights in float: a few ulps of the largest texel (1.0) at most.
    ASSERT_NEAR(f.r, d.r, 1e-5) << u << " " << v;
    ASSERT_NEAR(f.g, d.g, 1e-5);
    ASSERT_NEAR(f.b, d.b, 1e-5);
  }
}

TEST(TexelLookup, LanesReturnTheScalarFloatLookupLaneByLane) {
  TexelImage t = srgb_texels(9, 6);
  auto uv = coordinates(3);
  for (std::size_t i = 0; i + kW <= uv.size(); i += kW) {
    alignas(64) float u[kW], v[kW], r[kW], g[kW], b[kW];
    for (int k = 0; k < kW; ++k)
      u[k] = float(uv[i + k].first), v[k] = float(uv[i + k].second);
    simd::Mask<A> active = simd::first_lanes<A>(kW - 1);  // the last lane off
    RgbLanes<A> tex = texture_texel_lookup_lanes<A>(t, simd::load<A>(u), simd::load<A>(v), active);
    simd::store<A>(r, tex.r);
    simd::store<A>(g, tex.g);
    simd::store<A>(b, tex.b);
    for (int k = 0; k + 1 < kW; ++k) {
      LinearRgb<float> s = texture_texel_lookup<float>(t, u[k], v[k]);
      ASSERT_EQ(r[k], s.r);
      ASSERT_EQ(g[k], s.g);
      ASSERT_EQ(b[k], s.b);
    }
    EXPECT_EQ(r[kW - 1], 0.0f);
    RgbLanes<A> env =
        environment_texel_lookup_lanes<A>(t, simd::load<A>(u), simd::load<A>(v), active);
    simd::store<A>(r, env.r);
    for (int k = 0; k + 1 < kW; ++k)
      ASSERT_EQ(r[k], (environment_texel_lookup<float>(t, u[k], v[k]).r));
  }
}

}  // namespace
}  // namespace raylane
