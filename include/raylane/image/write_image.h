// Writing and reading image files by extension, atomically: a file is written to a temporary
// in the same directory and renamed into place, so a failed run never leaves a half-written
// or clobbered file (docs/scene-language.md, "Output").
#pragma once

#include <string>
#include <vector>

#include "raylane/core/atomic_file.h"  // check_writable
#include "raylane/core/error.h"
#include "raylane/image/image.h"

namespace raylane {

enum class ImageFormat { kHdr, kPfm, kPng };

// .hdr, .pfm or .png, case-insensitive.
Result<ImageFormat> format_from_path(const std::string& path);

struct WriteOptions {
  double exposure = 0;                // PNG: stops
  std::vector<std::string> metadata;  // HDR: extra KEY=value header lines
};

Status write_image(const std::string& path, const Image& image, const WriteOptions& options = {});
Result<Image> read_image(const std::string& path);  // .hdr and .pfm

}  // namespace raylane
