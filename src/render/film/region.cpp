#include "raylane/render/film/region.h"

#include <algorithm>
#include <memory>

#include "raylane/core/strings.h"

namespace raylane {

std::string region_text(const PixelRegion& r) {
  return cat(r.x0, ",", r.y0, ",", r.x1, ",", r.y1);
}

Status check_region(const PixelRegion& r, uint32_t width, uint32_t height) {
  if (r.x1 <= r.x0 || r.y1 <= r.y0)
    return Error{cat(region_text(r),
                     " is empty: X1 must be greater than X0, and Y1 than Y0 (X1 and Y1 are "
                     "exclusive)")};
  if (r.x1 > width || r.y1 > height)
    return Error{cat(region_text(r), " reaches past the ", width, "x", height,
                     " image: X1 may be at most ", width, " and Y1 at most ", height)};
  return ok_status();
}

bool region_meets_tile(const PixelRegion& r, uint32_t width, uint32_t height, uint64_t tile) {
  const uint64_t tiles_x = (uint64_t(width) + kPathTile - 1) / kPathTile;
  const uint64_t x0 = (tile % tiles_x) * kPathTile, y0 = (tile / tiles_x) * kPathTile;
  if (x0 >= r.x1 || x0 + kPathTile <= r.x0) return false;
  return region_meets_rows(r, height, uint32_t(y0), kPathTile);
}

bool region_meets_rows(const PixelRegion& r, uint32_t height, uint32_t y, uint32_t rows) {
  // Pixel-grid rows [y, y + rows) are image rows (height - y - rows, height - 1 - y].
  const int64_t top = int64_t(height) - int64_t(y) - int64_t(rows);  // may be < 0: a cut tile
  const int64_t bottom = int64_t(height) - 1 - int64_t(y);
  return top < int64_t(r.y1) && bottom >= int64_t(r.y0);
}

TileShare region_share(const TileShare& all, const PixelRegion& r, uint32_t width,
                       uint32_t height) {
  if (all.count <= 1) return all;
  const uint64_t tiles = ((uint64_t(width) + kPathTile - 1) / kPathTile) *
                         ((uint64_t(height) + kPathTile - 1) / kPathTile);
  std::vector<uint32_t> owner(tiles);
  uint32_t inside = 0, outside = 0;
  for (uint64_t t = 0; t < tiles; ++t)
    owner[t] =
        region_meets_tile(r, width, height, t) ? inside++ % all.count : outside++ % all.count;
  TileShare share = all;
  share.owner = std::make_shared<const std::vector<uint32_t>>(std::move(owner));
  return share;
}

std::vector<float> crop(const std::vector<float>& data, uint32_t width, std::size_t channels,
                        const PixelRegion& r) {
  std::vector<float> out;
  out.reserve(std::size_t(r.width()) * r.height() * channels);
  for (uint32_t y = r.y0; y < r.y1; ++y) {
    auto row = data.begin() + std::ptrdiff_t((std::size_t(y) * width + r.x0) * channels);
    out.insert(out.end(), row, row + std::ptrdiff_t(std::size_t(r.width()) * channels));
  }
  return out;
}

Image paste_region(const Image& part, const PixelRegion& r, uint32_t width, uint32_t height) {
  Image whole(width, height);
  for (uint32_t y = 0; y < part.height; ++y)
    std::copy_n(part.rgb.begin() + std::ptrdiff_t(std::size_t(y) * part.width * 3),
                std::size_t(part.width) * 3,
                whole.rgb.begin() + std::ptrdiff_t((std::size_t(y + r.y0) * width + r.x0) * 3));
  return whole;
}

Image crop(const Image& image, const PixelRegion& r) {
  Image out;
  out.width = r.width(), out.height = r.height();
  out.rgb = crop(image.rgb, image.width, 3, r);
  return out;
}

}  // namespace raylane
