#include "region_option.h"

#include <charconv>
#include <string_view>
#include <utility>

#include "raylane/core/strings.h"

namespace raylane::cli {

namespace {

constexpr const char* kCorners[4] = {"X0", "Y0", "X1", "Y1"};

Error bad_region(const std::string& value, const std::string& why) {
  return Error{
      cat("--region takes X0,Y0,X1,Y1, four whole numbers separated by commas (pixels "
          "from the top left, X1 and Y1 exclusive), found ",
          in_quotes(value), ": ", why)};
}

}  // namespace

Status read_region_option(const std::string& value, std::optional<PixelRegion>& out) {
  uint32_t corner[4] = {};
  std::string_view rest = value;
  for (int k = 0; k < 4; ++k) {
    std::size_t comma = rest.find(',');
    std::string_view part = rest.substr(0, comma);
    auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), corner[k]);
    if (ec != std::errc() || end != part.data() + part.size() || part.empty())
      return bad_region(value, cat(kCorners[k], " is ", in_quotes(std::string(part)),
                                   ec == std::errc::result_out_of_range ? " (too large)" : ""));
    if (k < 3 && comma == std::string_view::npos)
      return bad_region(value, cat("it has ", k + 1, " of the 4"));
    if (k == 3 && comma != std::string_view::npos) return bad_region(value, "it has more than 4");
    rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
  }
  PixelRegion r{corner[0], corner[1], corner[2], corner[3]};
  if (r.x1 <= r.x0 || r.y1 <= r.y0)
    return Error{cat("--region ", value,
                     " is empty: X1 must be greater than X0, and Y1 than Y0 (X1 and Y1 are "
                     "exclusive)")};
  out = r;
  return ok_status();
}

Status region_fits(const std::optional<PixelRegion>& region, const Scene& scene) {
  if (!region) return ok_status();
  if (Status s = check_region(*region, scene.width, scene.height); !s)
    return Error{cat("--region ", s.error(), " (the scene's screen, after any --set)")};
  return ok_status();
}

Image crop_to_region(Image image, const std::optional<PixelRegion>& region) {
  if (!region) return image;
  return crop(image, *region);
}

}  // namespace raylane::cli
