// Hostile inputs built in the test (docs/design.md, "Images in"), shared by the tests and the
// fuzzers' seeds: a PNG decompression bomb, a PLY whose header is longer than any buffer, an
// OpenEXR luminance-chroma file.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "raylane/core/vec_math.h"

namespace raylane::testing {

// A 1-bit grey PNG of w×h black pixels whose rows of zeros are deflated as runs of 258 bytes,
// 13 bits each (fixed Huffman codes, RFC 1951 3.2.6): 8192×8192 pixels, which decode to 64 Mi
// samples, take about 53 KB.
std::string png_zero_bomb(uint32_t w, uint32_t h);

// A Radiance HDR sky of w×h pixels of radiance 1, every row run-length encoded (runs of 127,
// Radiance's "new" RLE, so w is 8..32767): an 8192×4096 sky in 2.1 MB, as a real one's size
// order, without holding its floats.
std::string flat_hdr(uint32_t w, uint32_t h);

// A binary PLY of one triangle whose header holds `comment_bytes` of comment lines first.
std::string ply_with_long_header(std::size_t comment_bytes);

// An OpenEXR file of w×h pixels written by OpenEXR's RgbaOutputFile as luminance-chroma
// (Y full, RY and BY subsampled 2×2: WRITE_YC), from colour(x, y); ZIP compressed, Y and
// chroma kept to half precision (setYCRounding(10, 10)).
// With a data window whose top-left corner is (x0, y0) (a display window of the same place).
std::string exr_luminance_chroma(int w, int h, const std::function<glm::vec3(int, int)>& colour,
                                 int x0 = 0, int y0 = 0);

}  // namespace raylane::testing
