// The one texel lookup of textures and the environment, written once over the number type T:
// double for the reference path tracer, float for single-precision kernels (the float lanes run
// it lane by lane: render/materials/texel_lanes.h). docs/design.md, "Texel storage and lookup",
// states the contract:
// - coordinates in [0, 1) across the image, texel centres at (k + 1/2) / size;
// - bilinear between the four texel centres around the point (PBRT 3rd ed. §10.4.3);
// - textures repeat in u and v, with v UP the image (v = 0 is the file's bottom row); the
//   environment repeats in u (across φ = 0) and clamps in v, with v DOWN from the top row;
// - a non-finite coordinate, or an empty image, gives black;
// - the result is linear RGB: 8-bit texels go through the 256-entry sRGB table (image/texels.h).
// With T = double the arithmetic is the one the renderer has always done, so reference renders
// stay bit for bit what they were. `Texels` is a TexelImage, or a float Image (tests, tools):
// anything with width, height and at(x, y) → linear RGB.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "raylane/image/texels.h"

namespace raylane {

template <class T>
struct LinearRgb {
  T r = 0, g = 0, b = 0;
};

// The two texels around a coordinate and the weight of the second.
template <class T>
struct TexelSpan {
  uint32_t a = 0, b = 0;
  T w = 0;
};

// c in texels (centres at k + 1/2), repeating around `size`. A large |c| from far-off
// coordinates loses fraction bits, never range.
template <class T>
TexelSpan<T> repeat_span(T c, uint32_t size) {
  T x = c - T(0.5);
  T f = std::floor(x);
  T w = x - f;
  // f − ⌊f/n⌋·n, without the division where f lies within a turn of the image (every lookup of
  // a coordinate in [0, 1)): ⌊f/n⌋ is 0 or −1 there, so these are the same values. The
  // division's latency was the wait of every environment lookup's first texel load (perf).
  const T n = T(size);
  T m = f >= 0 && f < n ? f : f < 0 && f >= -n ? f + n : f - std::floor(f / n) * n;
  uint32_t a = m >= 0 && m < T(size) ? uint32_t(m) : 0;
  return {a, a + 1 == size ? 0 : a + 1, w};
}

// c in texels within [0, size], the edge texels held beyond the outer centres.
template <class T>
TexelSpan<T> clamp_span(T c, uint32_t size) {
  T x = c - T(0.5);
  T f = std::floor(x);
  int64_t i = int64_t(f);
  auto clamp = [&](int64_t k) { return uint32_t(std::clamp<int64_t>(k, 0, int64_t(size) - 1)); };
  return {clamp(i), clamp(i + 1), x - f};
}

template <class T>
LinearRgb<T> mix_rgb(const LinearRgb<T>& p, const LinearRgb<T>& q, T w) {
  return {p.r * (1 - w) + q.r * w, p.g * (1 - w) + q.g * w, p.b * (1 - w) + q.b * w};
}

// Bilinear between columns sx.a, sx.b and image rows row_a, row_b (row 0 = top), weight wy on
// row_b; fetch(x, y) gives a texel as linear RGB floats.
template <class T, class Fetch>
LinearRgb<T> bilinear_fetch(const Fetch& fetch, const TexelSpan<T>& sx, uint32_t row_a,
                            uint32_t row_b, T wy) {
  auto texel = [&](uint32_t x, uint32_t y) {
    glm::vec3 c = fetch(x, y);
    return LinearRgb<T>{T(c.x), T(c.y), T(c.z)};
  };
  LinearRgb<T> first = mix_rgb(texel(sx.a, row_a), texel(sx.b, row_a), sx.w);
  LinearRgb<T> second = mix_rgb(texel(sx.a, row_b), texel(sx.b, row_b), sx.w);
  return mix_rgb(first, second, wy);
}

// Any image with at(x, y) (a float Image).
template <class T, class Texels>
LinearRgb<T> bilinear(const Texels& img, const TexelSpan<T>& sx, uint32_t row_a, uint32_t row_b,
                      T wy) {
  return bilinear_fetch([&](uint32_t x, uint32_t y) { return img.at(x, y); }, sx, row_a, row_b, wy);
}

// Texels: the storage form is chosen once per lookup, not once per texel.
template <class T>
LinearRgb<T> bilinear(const TexelImage& img, const TexelSpan<T>& sx, uint32_t row_a, uint32_t row_b,
                      T wy) {
  const std::size_t w = img.width;
  switch (img.format) {
    case TexelFormat::kSrgb8: {
      const uint32_t* p = img.packed.data();
      const float* t = srgb8_table().data();
      auto fetch = [=](uint32_t x, uint32_t y) {
        uint32_t c = p[y * w + x];
        return glm::vec3(t[c & 0xff], t[(c >> 8) & 0xff], t[(c >> 16) & 0xff]);
      };
      return bilinear_fetch(fetch, sx, row_a, row_b, wy);
    }
    case TexelFormat::kRgbe: {
      const uint32_t* p = img.packed.data();
      auto fetch = [=](uint32_t x, uint32_t y) { return TexelImage::rgbe_texel(p[y * w + x]); };
      return bilinear_fetch(fetch, sx, row_a, row_b, wy);
    }
    case TexelFormat::kHalf: {
      const uint16_t* h = img.half.data();
      auto fetch = [=](uint32_t x, uint32_t y) {
        const uint16_t* c = h + 3 * (y * w + x);
        return glm::vec3(half_to_float(c[0]), half_to_float(c[1]), half_to_float(c[2]));
      };
      return bilinear_fetch(fetch, sx, row_a, row_b, wy);
    }
    case TexelFormat::kFloat:
      break;
  }
  const float* f = img.rgb.data();
  auto fetch = [=](uint32_t x, uint32_t y) {
    const float* c = f + 3 * (y * w + x);
    return glm::vec3(c[0], c[1], c[2]);
  };
  return bilinear_fetch(fetch, sx, row_a, row_b, wy);
}

// A texture at (u, v): u to the right, v up, repeating both ways.
template <class T, class Texels>
LinearRgb<T> texture_texel_lookup(const Texels& img, T u, T v) {
  if (img.width == 0 || img.height == 0 || !std::isfinite(u) || !std::isfinite(v)) return {};
  u -= std::floor(u);
  v -= std::floor(v);
  TexelSpan<T> sx = repeat_span(u * T(img.width), img.width);
  TexelSpan<T> sy = repeat_span(v * T(img.height), img.height);  // rows counted from the bottom
  return bilinear(img, sx, img.height - 1 - sy.a, img.height - 1 - sy.b, sy.w);
}

// The environment's image at (u, v): u to the right, v down from the top row, repeating in u
// and clamped in v. Unscaled.
template <class T, class Texels>
LinearRgb<T> environment_texel_lookup(const Texels& img, T u, T v) {
  if (img.width == 0 || img.height == 0 || !std::isfinite(u) || !std::isfinite(v)) return {};
  TexelSpan<T> sx = repeat_span((u - std::floor(u)) * T(img.width), img.width);
  TexelSpan<T> sy = clamp_span(std::clamp(v, T(0), T(1)) * T(img.height), img.height);
  return bilinear(img, sx, sy.a, sy.b, sy.w);
}

}  // namespace raylane
