// OpenEXR (.exr) files through Debian's OpenEXR 3.1 (the file layout: "OpenEXR File Layout",
// openexr.com). raylane writes one single-part scanline image, ZIP-compressed (16 lines per
// block), RGB as 32-bit float or 16-bit half, plus optional extra layers whose channels are
// named LAYER.CHANNEL ("albedo.R", "normal.X", "depth.Z"), the convention EXR viewers group by.
//
// Reading goes through OpenEXR's C core (OpenEXRCore), which reports every problem as an
// error code rather than an exception, and which lets the header be checked before any pixel
// is allocated (docs/design.md, "Images in"): one scanline part, a data window within the
// 2^28-pixel limit, a chunk table and compressed data that a file of this length can hold.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/image/image.h"

namespace raylane {

// Extra channels beside RGB, all of one layer: stored as "<name>.<channel>".
struct ExrLayer {
  std::string name;                   // "albedo"; not empty, dots only between parts
  std::vector<std::string> channels;  // "R", "G", "B" or "X", "Y", "Z" or "Z"; no '.'
  std::vector<float> data;            // width·height·channels.size(), interleaved, top row first
};

struct ExrWriteOptions {
  bool half = false;                  // 16-bit half channels instead of 32-bit float
  std::vector<std::string> metadata;  // KEY=value lines → string attributes named KEY
};

// Writes the image as R, G, B and the layers to `f` (raylane's atomic writer hands it the
// temporary file). Half output clamps to the largest half (65504) so that no value becomes
// infinite. Errors: a layer of the wrong size or with a bad name, a metadata line without
// '=' or naming an attribute the format defines itself, a failed write.
Status write_exr(std::FILE* f, const Image& image, const std::vector<ExrLayer>& layers = {},
                 const ExrWriteOptions& options = {});

// What the header says, checked as decode_exr checks it.
struct ExrInfo {
  uint32_t width = 0, height = 0;     // of the data window
  std::vector<std::string> channels;  // full names, in the file's (alphabetical) order
  std::vector<std::string> metadata;  // string attributes as KEY=value, in file order
  std::vector<std::string> layers;    // the distinct prefixes before the last '.'; "" first if
                                      // some channel has no prefix
  bool has_rgb = false, has_y = false;
};

Result<ExrInfo> probe_exr(std::string_view bytes);

// The image as linear RGB, top row first: R, G, B if the file has all three, else Y as grey.
// Values are returned as stored (NaN, infinities and negatives too): the texture reader
// refuses those, `raylane diff` counts them.
Result<Image> decode_exr(std::string_view bytes);

// One layer's channels ("" = the channels without a '.'), interleaved in the file's order.
Result<ExrLayer> decode_exr_layer(std::string_view bytes, std::string_view layer);

// Does `bytes` start with the EXR magic number (0x76 0x2f 0x31 0x01)?
bool is_exr(std::string_view bytes);

}  // namespace raylane
