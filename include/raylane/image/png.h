// 8-bit sRGB PNG through libpng: pixel·2^exposure, clamped to [0, 1], sRGB-encoded
// (IEC 61966-2-1), rounded to nearest.
#pragma once

#include <cstdint>
#include <cstdio>

#include "raylane/core/error.h"
#include "raylane/image/image.h"

namespace raylane {

uint8_t srgb_encode_8bit(float linear);  // clamp to [0, 1], encode, round
Status write_png(std::FILE* f, const Image& image, double exposure);

}  // namespace raylane
