// Portable float maps (.pfm), colour: `PF`, `W H`, a scale whose sign gives the byte order
// (−1: little endian), then rows of 3 float32 per pixel, BOTTOM row first (Paul Debevec's
// HDRShop format definition).
#pragma once

#include <string>
#include <string_view>

#include "raylane/core/error.h"
#include "raylane/image/image.h"

namespace raylane {

std::string encode_pfm(const Image& image);
Result<Image> decode_pfm(std::string_view bytes);

}  // namespace raylane
