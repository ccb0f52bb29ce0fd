// The images `raylane convert` and `raylane diff` read: raylane's own outputs (.hdr, .pfm, .exr,
// which may hold any float, as a render or an AOV does) and every format a texture may be
// (PNG, JPEG, TGA, BMP: sRGB-encoded, read as linear RGB as textures are).
#pragma once

#include <string>

#include "raylane/core/error.h"
#include "raylane/image/image.h"

namespace raylane::cli {

Result<Image> read_any_image(const std::string& path);

}  // namespace raylane::cli
