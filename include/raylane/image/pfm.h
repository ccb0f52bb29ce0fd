// Portable float maps (.pfm): `PF` (colour) or `Pf` (grey), `W H`, a scale whose sign gives the
// byte order (−1: little endian), then rows of 3 (or 1) float32 per pixel, BOTTOM row first
// (Paul Debevec's HDRShop format definition). raylane writes colour; it reads both, grey as
// three equal channels.
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
  int channels = 3;             // 3 for PF, 1 for Pf
  double scale = 0;             // its sign gives the byte order; finite and not 0
  std::size_t data_offset = 0;  // where the pixels start
};

std::string encode_pfm(const Image& image);
// The header, checked: a size within the limit and a file long enough to hold its pixels.
Result<PfmHeader> parse_pfm_header(std::string_view bytes);
Result<Image> decode_pfm(std::string_view bytes);

}  // namespace raylane
