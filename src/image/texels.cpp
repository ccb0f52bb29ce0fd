#include "raylane/image/texels.h"

#include <cmath>

#include "raylane/image/input_image.h"

namespace raylane {

const char* texel_format_name(TexelFormat f) {
  switch (f) {
    case TexelFormat::kSrgb8:
      return "8-bit sRGB";
    case TexelFormat::kRgbe:
      return "RGBE";
    case TexelFormat::kHalf:
      return "half";
    case TexelFormat::kFloat:
      return "float";
  }
  return "float";
}

uint32_t texel_bytes(TexelFormat f) {
  switch (f) {
    case TexelFormat::kSrgb8:
    case TexelFormat::kRgbe:
      return 4;
    case TexelFormat::kHalf:
      return 6;
    case TexelFormat::kFloat:
      return 12;
  }
  return 12;
}

const std::array<float, 256> kSrgb8ToLinear = [] {
  std::array<float, 256> t{};
  for (int i = 0; i < 256; ++i)
    t[i] = float(srgb_to_linear(i / 255.0));
  return t;
}();

const std::array<float, 256> kRgbeScale = [] {
  std::array<float, 256> t{};
  for (int e = 1; e < 256; ++e)
    t[e] = std::ldexp(1.0f, e - 136);
  return t;
}();

// A half holds f exactly when f is 0, a subnormal half (m · 2^-24, m < 1024) or a normal half
// (exponent −14…15, the float's mantissa zero below its top 10 bits). IEEE 754-2008 §3.6.
bool float_to_half_exactly(float f, uint16_t& out) {
  if (!(f >= 0) || !std::isfinite(f)) return false;
  if (f < 0x1p-14f) {
    float m = f * 0x1p24f;  // exact: a power-of-two scale of a small float
    if (m != std::floor(m) || m >= 1024) return false;
    out = uint16_t(m);
    return true;
  }
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  int exp = int((bits >> 23) & 0xff) - 127;
  if (exp > 15 || (bits & 0x1fffu) != 0) return false;
  out = uint16_t(uint32_t(exp + 15) << 10 | ((bits >> 13) & 0x3ffu));
  return true;
}

TexelImage srgb8_texels(uint32_t width, uint32_t height, const std::vector<uint8_t>& rgb8) {
  TexelImage t;
  t.width = width, t.height = height, t.format = TexelFormat::kSrgb8;
  t.packed.resize(t.texel_count());
  for (std::size_t i = 0; i < t.packed.size(); ++i)
    t.packed[i] =
        uint32_t(rgb8[3 * i]) | uint32_t(rgb8[3 * i + 1]) << 8 | uint32_t(rgb8[3 * i + 2]) << 16;
  return t;
}

TexelImage float_texels(Image image) {
  TexelImage t;
  t.width = image.width, t.height = image.height;
  // Checked before the halves are allocated, so a float image takes no second buffer.
  bool exact = true;
  uint16_t h = 0;
  for (std::size_t i = 0; i < image.rgb.size() && exact; ++i)
    exact = float_to_half_exactly(image.rgb[i], h);
  if (exact) {
    t.format = TexelFormat::kHalf;
    t.half.resize(image.rgb.size());
    for (std::size_t i = 0; i < image.rgb.size(); ++i)
      float_to_half_exactly(image.rgb[i], t.half[i]);
  } else {
    t.format = TexelFormat::kFloat;
    t.rgb = std::move(image.rgb);
  }
  return t;
}

Image to_float_image(const TexelImage& t) {
  Image img(t.width, t.height);
  for (uint32_t y = 0; y < t.height; ++y)
    for (uint32_t x = 0; x < t.width; ++x)
      img.set(x, y, t.at(x, y));
  return img;
}

}  // namespace raylane
