// Writing and reading image files by extension, atomically: a file is written to a temporary
// in the same directory and renamed into place, so a failed run never leaves a half-written
// or clobbered file (docs/scene-language.md, "Output").
#pragma once

#include <string>
#include <vector>

#include "raylane/core/atomic_file.h"  // check_writable
#include "raylane/core/error.h"
#include "raylane/image/exr.h"
#include "raylane/image/image.h"

namespace raylane {

enum class ImageFormat { kHdr, kPfm, kPng, kExr };

// .hdr, .pfm, .png or .exr, case-insensitive.
Result<ImageFormat> format_from_path(const std::string& path);

struct WriteOptions {
  double exposure = 0;                // PNG: stops
  std::vector<std::string> metadata;  // HDR: extra KEY=value header lines; EXR: string attributes
  bool exr_half = false;              // EXR: 16-bit half channels instead of 32-bit float
  // EXR: layers beside RGB (image/exr.h). The other formats hold RGB only and ignore them, so
  // that the rescue file of a failed write (image/write_fallback.h) still keeps the picture.
  std::vector<ExrLayer> exr_layers;
};

Status write_image(const std::string& path, const Image& image, const WriteOptions& options = {});
Result<Image> read_image(const std::string& path);  // .hdr, .pfm and .exr

}  // namespace raylane
