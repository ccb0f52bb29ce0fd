// JPEG files for the tests and the fuzzer's seeds, written with libjpeg-turbo's compressor:
// ordinary ones, and the kinds raylane refuses (arithmetic-coded, CMYK, too many scans).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace raylane::testing {

enum class JpegKind {
  kBaseline,     // Huffman, sequential
  kProgressive,  // libjpeg's default progression (about 10 scans)
  kManyScans,    // progressive, one scan per AC coefficient and component: 190 scans in colour
  kArithmetic,   // arithmetic-coded
};

// `samples` holds `components` bytes per pixel, top row first: 1 grey, 3 RGB, 4 CMYK.
// Quality 100 and no chroma subsampling, so flat 8×8 blocks come back within a code or two.
std::string jpeg_bytes(const std::vector<uint8_t>& samples, uint32_t width, uint32_t height,
                       int components, JpegKind kind = JpegKind::kBaseline);

}  // namespace raylane::testing
