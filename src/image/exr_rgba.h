// Luminance-chroma EXR files (Y at full resolution, RY and BY subsampled 2×2: what OpenEXR's
// RgbaOutputFile writes in its WRITE_YC modes) through OpenEXR's own RGBA interface, which
// reconstructs RGB from them (filtering the chroma up and converting with the file's
// chromaticities, "Reading and Writing OpenEXR Image Files with the IlmImf Library",
// "Luminance/Chroma Images"). Internal to src/image: exr.cpp checks the header first.
#pragma once

#include <cstdint>
#include <string_view>

#include "raylane/core/error.h"
#include "raylane/image/image.h"

namespace raylane::exr_detail {

// The image as linear RGB, top row first; alpha is dropped. Call only once OpenEXRCore has
// checked the header (size within the pixel limit, chunk table within the file) and read its
// data window as width x height: a file whose header reads to OpenEXR's C++ reader at any
// other size is refused before that reader allocates anything by the window.
Result<Image> decode_rgba_interface(std::string_view bytes, uint32_t width, uint32_t height);

}  // namespace raylane::exr_detail
