// Radiance RGBE (.hdr) files: Greg Ward's shared-exponent format ("Real Pixels", Graphics
// Gems II, 1991; the Radiance file format documentation). Header `#?RADIANCE`, key=value
// lines, a blank line, `-Y H +X W`, then scanlines, run-length encoded ("new" RLE) for widths
// 8..32767 and flat otherwise.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/image/image.h"
#include "raylane/image/texels.h"

namespace raylane {

// One pixel: mantissas scaled so the largest channel has its top bit set, and a shared
// exponent biased by 128. Negatives and NaN encode as 0; +inf as the largest encodable value.
std::array<uint8_t, 4> float_to_rgbe(float r, float g, float b);
glm::vec3 rgbe_to_float(const std::array<uint8_t, 4>& e);

// The whole file. `metadata` lines (KEY=value) go into the header after SOFTWARE=raylane.
std::string encode_rgbe(const Image& image, const std::vector<std::string>& metadata = {});

struct RgbeFile {
  Image image;
  std::vector<std::string> metadata;  // header lines other than the magic and FORMAT
};

// Reads a whole file. Hostile input gives an error, never a crash or a huge allocation.
Result<RgbeFile> decode_rgbe(std::string_view bytes);
// The same pixels as their RGBE bytes (image/texels.h, TexelFormat::kRgbe): 4 bytes a pixel
// where the float image takes 12, and decoding to exactly the floats decode_rgbe returns.
Result<TexelImage> decode_rgbe_texels(std::string_view bytes);

// The size the header announces (checked as decode_rgbe checks it), without a pixel decoded:
// `bytes` may be the file's beginning only.
struct RgbeSize {
  uint32_t width = 0, height = 0;
};
Result<RgbeSize> probe_rgbe(std::string_view bytes);

}  // namespace raylane
