// Portable float maps (.pfm), colour: `PF`, `W H`, a scale whose sign gives the byte order
// (−1: little endian), then rows of 3 float32 per pixel, BOTTOM row first (Paul Debevec's
// HDRShop format definition).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "raylane/core/error.h"
#include "raylane/image/image.h"

namespace raylane {

struct PfmHeader {
  uint32_t width = 0, height = 0;
  double scale = 0;             // its sign gives the byte order
  std::size_t data_offset = 0;  // where the pixels start
};

std::string encode_pfm(const Image& image);
// The header, checked: a size within the limit and a file long enough to hold its pixels.
Result<PfmHeader> parse_pfm_header(std::string_view bytes);
Result<Image> decode_pfm(std::string_view bytes);

}  // namespace raylane
