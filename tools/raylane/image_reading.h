// The images `raylane convert` and `raylane diff` read: raylane's own outputs (.hdr, .pfm, .exr,
// which may hold any float, as a render or an AOV does) and every format a texture may be
// (PNG, JPEG, TGA, BMP: sRGB-encoded, read as linear RGB as textures are). Their headers are read
// first, and the whole command's image memory (--image-memory, with `render`'s rules: the
// default budget and the decompression-bomb rule) is checked before any pixel is decoded.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/core/memory.h"
#include "raylane/image/image.h"

namespace raylane::cli {

struct ImageMemoryOption {
  uint64_t bytes = default_image_memory();
  bool chosen = false;  // --image-memory given
};

// An image's header and what decoding it to floats takes.
struct ImageHeader {
  std::string path;
  uint32_t width = 0, height = 0;
  uint64_t decode = 0, file_bytes = 0;
  uint64_t float_bytes() const { return uint64_t(width) * height * 3 * sizeof(float); }
};

Result<ImageHeader> read_any_header(const std::string& path);

// Whether decoding `images` in turn, each kept as floats while the next decodes, and then
// `after` more bytes (a heatmap), fit the image memory: an error naming the figure that does
// otherwise.
Status check_images_memory(const std::vector<ImageHeader>& images, uint64_t after,
                           const ImageMemoryOption& memory);

// The image whose header was read and checked.
Result<Image> read_any_image(const ImageHeader& header);

}  // namespace raylane::cli
