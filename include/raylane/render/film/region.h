// A pixel rectangle of the image (`raylane render --region`, pbrt's --pixelbounds): only the
// tiles that meet it are rendered, and the files hold it alone. Its pixels are bit for bit
// those of a whole render with the same settings: a region renders whole tiles, since a tile's
// MT19937-64 stream is drawn pixel by pixel in the tile's order (Rng::for_tile), and Sobol's
// numbers are a function of the pixel.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/image/image.h"
#include "raylane/render/film/tile_share.h"

namespace raylane {

// Columns [x0, x1) and rows [y0, y1), rows counted from the top as image files store them.
struct PixelRegion {
  uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  uint32_t width() const { return x1 - x0; }
  uint32_t height() const { return y1 - y0; }
  bool operator==(const PixelRegion&) const = default;
};

// "X0,Y0,X1,Y1", as --region takes it and the headers record it.
std::string region_text(const PixelRegion& r);

// An error unless the region is non-empty and lies within a width × height image; the message
// starts with region_text(r).
Status check_region(const PixelRegion& r, uint32_t width, uint32_t height);

// Whether path tile t (kPathTile pixels square, numbered row-major from the bottom row of
// pixels up: tile_share.h) of a width × height image has a pixel in the region.
bool region_meets_tile(const PixelRegion& r, uint32_t width, uint32_t height, uint64_t tile);

// The ray-casting band of rows [y, y + rows) of the pixel grid (y counting up from the bottom)
// has a row in the region.
bool region_meets_rows(const PixelRegion& r, uint32_t height, uint32_t y, uint32_t rows);

// The processes' share of the tiles for a region: its tiles dealt round-robin in tile order,
// so that each process gets as many as the others (dealing all the image's tiles, a region one
// tile wide would fall to one process when the tiles per row are a multiple of the count).
// Tiles outside the region go round-robin too; no process renders them.
TileShare region_share(const TileShare& all, const PixelRegion& r, uint32_t width, uint32_t height);

constexpr std::size_t kNotInRegion = ~std::size_t(0);

// Where a region-sized buffer keeps pixel `pixel` (y·width + x, top row first) of a
// `width`-wide image: its index in the region's rows, kNotInRegion outside it; the pixel
// itself without a region.
inline std::size_t region_slot(const std::optional<PixelRegion>& r, uint32_t width,
                               std::size_t pixel) {
  if (!r) return pixel;
  const std::size_t x = pixel % width, y = pixel / width;
  if (x < r->x0 || x >= r->x1 || y < r->y0 || y >= r->y1) return kNotInRegion;
  return (y - r->y0) * r->width() + (x - r->x0);
}

// A region's image put in its place in a width × height image, black elsewhere (the inverse
// of crop, for a viewer that shows the whole screen).
Image paste_region(const Image& part, const PixelRegion& r, uint32_t width, uint32_t height);

// The region of an image, or of `channels` interleaved floats per pixel of a `width`-wide
// image (rows top first, as both store them).
Image crop(const Image& image, const PixelRegion& r);
std::vector<float> crop(const std::vector<float>& data, uint32_t width, std::size_t channels,
                        const PixelRegion& r);

}  // namespace raylane
