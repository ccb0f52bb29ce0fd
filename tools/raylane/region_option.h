// `--region X0,Y0,X1,Y1` of `raylane render` (render/film/region.h): read from the option, checked
// against the screen once the scene is loaded, and what it does to the files written.
#pragma once

#include <optional>
#include <string>

#include "raylane/core/error.h"
#include "raylane/render/film/region.h"
#include "render_request.h"

namespace raylane::cli {

inline constexpr const char* kRegionHelp =
    "render and write only this pixel rectangle: columns X0 to X1 and rows\n"
    "Y0 to Y1 from the top left, X1 and Y1 exclusive (an image of\n"
    "(X1-X0)x(Y1-Y0)); its pixels are those of the whole render, bit for bit";

// "X0,Y0,X1,Y1": four whole numbers, X0 < X1 and Y0 < Y1.
Status read_region_option(const std::string& value, std::optional<PixelRegion>& out);

// The region within the scene's screen (known only once --set lines are read).
Status region_fits(const std::optional<PixelRegion>& region, const Scene& scene);

// The region of an image the size of the screen; without a region, the image.
Image crop_to_region(Image image, const std::optional<PixelRegion>& region);

}  // namespace raylane::cli
