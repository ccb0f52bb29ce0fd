// The texels a scene keeps for its textures and its environment, stored as compactly as the file
// held them (docs/design.md, "Texel storage and lookup"):
// - 8-bit sRGB files (8-bit PNG, JPEG, BMP, TGA): the encoded bytes, 4 bytes a texel, decoded
//   at lookup through a 256-entry table of the sRGB transfer function's inverse;
// - Radiance HDR: the file's shared-exponent RGBE bytes, 4 bytes a texel (Ward, "Real Pixels",
//   Graphics Gems II), decoded at lookup as the reader decoded them;
// - float images (OpenEXR, PFM, 16-bit PNG) whose every value a binary16 half holds exactly
//   (an EXR written in half): 3 halves, 6 bytes a texel;
// - the others: 3 binary32 floats, 12 bytes a texel.
// Every form decodes to exactly the float the reader returns for that texel (read_input_image),
// so renders do not change with the storage.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "raylane/core/vec_math.h"
#include "raylane/image/image.h"

namespace raylane {

enum class TexelFormat : uint8_t { kSrgb8, kRgbe, kHalf, kFloat };

const char* texel_format_name(TexelFormat f);
// The bytes one texel takes in the format.
uint32_t texel_bytes(TexelFormat f);

// The decoding tables, filled before main (texels.cpp), so that a lookup reads them without a
// guard: the sRGB table's entry i is the linear value of the encoded byte i (IEC 61966-2-1), the
// float srgb_to_linear(i / 255.0) rounds to; the RGBE table's entry E is 2^(E − 136) as Radiance
// scales a mantissa byte (image/rgbe.h, rgbe_to_float), and 0 for E = 0.
extern const std::array<float, 256> kSrgb8ToLinear;
extern const std::array<float, 256> kRgbeScale;
inline const std::array<float, 256>& srgb8_table() {
  return kSrgb8ToLinear;
}

// IEEE 754 binary16 → binary32, exactly (every half is a float).
inline float half_to_float(uint16_t h) {
  uint32_t sign = uint32_t(h & 0x8000u) << 16, exp = (h >> 10) & 0x1fu, mant = h & 0x3ffu;
  if (exp == 0) {  // zero or subnormal: mant · 2^-24, exact in float
    float f = float(mant) * 0x1p-24f;
    return sign ? -f : f;
  }
  uint32_t bits =
      sign | (exp == 31 ? 0x7f800000u | (mant << 13) : ((exp + 112) << 23) | (mant << 13));
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}
// The half that holds f exactly, if one does (finite, non-negative values only).
bool float_to_half_exactly(float f, uint16_t& out);

struct TexelImage {
  uint32_t width = 0, height = 0;
  TexelFormat format = TexelFormat::kFloat;
  std::vector<uint32_t>
      packed;  // kSrgb8: R | G << 8 | B << 16; kRgbe: R | G << 8 | B << 16 | E << 24
  std::vector<uint16_t> half;  // kHalf: R, G, B per texel
  std::vector<float> rgb;      // kFloat: R, G, B per texel

  std::size_t texel_count() const { return std::size_t(width) * height; }
  bool empty() const { return width == 0 || height == 0; }
  // What the texels hold in memory.
  std::size_t bytes() const {
    return packed.capacity() * 4 + half.capacity() * 2 + rgb.capacity() * 4;
  }
  // Column x, row y (row 0 = the top row, as files store it): linear RGB.
  glm::vec3 at(uint32_t x, uint32_t y) const {
    std::size_t i = std::size_t(y) * width + x;
    switch (format) {
      case TexelFormat::kSrgb8: {
        const auto& t = srgb8_table();
        uint32_t p = packed[i];
        return {t[p & 0xff], t[(p >> 8) & 0xff], t[(p >> 16) & 0xff]};
      }
      case TexelFormat::kRgbe:
        return rgbe_texel(packed[i]);
      case TexelFormat::kHalf:
        return {half_to_float(half[3 * i]), half_to_float(half[3 * i + 1]),
                half_to_float(half[3 * i + 2])};
      case TexelFormat::kFloat:
        break;
    }
    return {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]};
  }

  // Radiance's decoding (image/rgbe.h, rgbe_to_float): mantissa · 2^(E − 136), 0 when E = 0.
  static glm::vec3 rgbe_texel(uint32_t p) {
    float f = kRgbeScale[p >> 24];
    return {float(p & 0xff) * f, float((p >> 8) & 0xff) * f, float((p >> 16) & 0xff) * f};
  }
};

// Texels from 8-bit sRGB samples (3 a texel, top row first).
TexelImage srgb8_texels(uint32_t width, uint32_t height, const std::vector<uint8_t>& rgb8);
// Texels from linear floats (3 a texel), in half when every value is a half exactly, else as
// floats. Takes the buffer, so that no second float copy is made.
TexelImage float_texels(Image image);
// Every texel as linear RGB floats: `convert`, `diff` and the film's fingerprint see the
// values the scene's lookups see.
Image to_float_image(const TexelImage& t);

}  // namespace raylane
