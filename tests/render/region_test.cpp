// --region (render/film/region.h): the rectangle's pixels are bit for bit those of a whole render
// with the same settings, for both samplers and every ray-casting view; only the tiles and
// bands that meet it are traced; a film records its region.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "raylane/bvh/bvh.h"
#include "raylane/core/strings.h"
#include "raylane/render/film/film.h"
#include "raylane/render/film/region.h"
#include "raylane/render/path.h"
#include "raylane/render/raycast.h"
#include "raylane/scene/parser.h"
#include "support/paths.h"
#include "support/same_bits.h"

namespace raylane {
namespace {

// The course scene at 72×52: a partial tile column and row (the render numbers tiles from
// the bottom row up, images store rows from the top), and a lit sphere among the boxes.
struct World {
  Scene scene;
  Bvh bvh;
};

World course_scene() {
  auto p = load_scene_file(testing::source_path("scenes/testscene.scn"));
  EXPECT_TRUE(p.ok());
  World w{std::move(p.scene), {}};
  w.scene.width = 72, w.scene.height = 52;
  w.bvh = build_bvh_and_reorder(w.scene);
  return w;
}

// Regions inside one tile, across tile borders, at the cut tiles of the right and bottom
// edges, one pixel at a corner, and the whole image.
const PixelRegion kRegions[] = {{5, 7, 9, 10},  {10, 3, 40, 30}, {60, 40, 72, 52},
                                {0, 51, 1, 52}, {71, 0, 72, 1},  {0, 0, 72, 52}};

// The tiles a region meets, by their pixels: the oracle for region_meets_tile.
uint64_t tiles_met_by_pixels(const PixelRegion& r, uint32_t width, uint32_t height) {
  uint64_t met = 0;
  const uint32_t tiles_x = (width + kPathTile - 1) / kPathTile;
  const uint32_t tiles_y = (height + kPathTile - 1) / kPathTile;
  for (uint32_t t = 0; t < tiles_x * tiles_y; ++t) {
    bool any = false;
    for (uint32_t row = 0; row < height; ++row)
      for (uint32_t x = 0; x < width; ++x)
        any |= tile_of_film_pixel(width, height, x, row) == t && x >= r.x0 && x < r.x1 &&
               row >= r.y0 && row < r.y1;
    met += any;
  }
  return met;
}

// Pixels of the whole film's tiles that the region meets (what a region render traces).
uint64_t pixels_of_tiles_met(const PixelRegion& r, uint32_t width, uint32_t height) {
  uint64_t n = 0;
  for (uint32_t row = 0; row < height; ++row)
    for (uint32_t x = 0; x < width; ++x)
      n += region_meets_tile(r, width, height, tile_of_film_pixel(width, height, x, row));
  return n;
}

// `part` holds the region's pixels alone, in its rows; `whole` every pixel of the image.
void expect_same_region(const std::vector<double>& whole, const std::vector<double>& part,
                        uint32_t width, std::size_t channels, const PixelRegion& r) {
  ASSERT_EQ(part.size(), std::size_t(r.width()) * r.height() * channels);
  std::size_t differing = 0, at = 0;
  for (uint32_t y = r.y0; y < r.y1; ++y)
    for (uint32_t x = r.x0; x < r.x1; ++x)
      for (std::size_t k = 0; k < channels; ++k, ++at) {
        std::size_t i = (std::size_t(y) * width + x) * channels + k;
        differing += !testing::same_bits(whole[i], part[at]);
      }
  EXPECT_EQ(differing, 0u);
}

TEST(Region, PathPixelsAreTheWholeRendersBitForBitForEverySampler) {
  World w = course_scene();
  Tracer tracer(w.scene, w.bvh, TracerBackend::kPacket);
  for (Sampler sampler : {Sampler::kMt19937, Sampler::kSobol}) {
    PathSettings s;
    s.spp = 3, s.seed = 5, s.sampler = sampler;
    s.aovs = *parse_aov_list("albedo,depth");
    Film whole;
    render_path(tracer, s, nullptr, &whole);
    for (const PixelRegion& r : kRegions) {
      SCOPED_TRACE(cat(sampler_name(sampler), " ", region_text(r)));
      PathSettings rs = s;
      rs.region = r;
      Film part;
      PathStats stats;
      render_path(tracer, rs, &stats, &part);
      expect_same_region(whole.sum, part.sum, 72, 3, r);
      expect_same_region(whole.aov_sum, part.aov_sum, 72, std::size_t(s.aovs.channels()), r);
      // Whole tiles are traced, and no others: one camera ray per pixel of them per pass.
      EXPECT_EQ(stats.camera_rays, pixels_of_tiles_met(r, 72, 52) * 3);
      Image cut = part.image();
      ASSERT_EQ(cut.width, r.width());
      ASSERT_EQ(cut.height, r.height());
      EXPECT_EQ(cut.rgb, crop(whole.image(), r).rgb);
    }
  }
}

TEST(Region, RayCastPixelsAreTheWholeViewsBitForBit) {
  World w = course_scene();
  Tracer tracer(w.scene, w.bvh, TracerBackend::kPacket);
  for (std::size_t m = 0; m < kRaycastModeNames.names.size(); ++m) {
    const RaycastMode mode = RaycastMode(m);
    Image whole = render_raycast(tracer, mode);
    for (const PixelRegion& r : kRegions) {
      SCOPED_TRACE(cat(raycast_mode_name(mode), " ", region_text(r)));
      RaycastStats stats;
      Image part = render_raycast(tracer, mode, &stats, r);
      Image cut = part, expected = crop(whole, r);
      ASSERT_EQ(cut.width, r.width());
      ASSERT_EQ(cut.height, r.height());
      std::size_t differing = 0;
      for (std::size_t i = 0; i < cut.rgb.size(); ++i)
        differing += !testing::same_bits(cut.rgb[i], expected.rgb[i]);
      EXPECT_EQ(differing, 0u);
      // Only the 16-row bands that meet the region are traced.
      if (r.height() < 16) {
        EXPECT_LE(stats.camera_rays, 2u * 16 * 72);
      }
    }
  }
}

TEST(Region, TilesAndBandsMetAreThoseHoldingItsPixels) {
  for (auto [width, height] : {std::pair{72u, 52u}, std::pair{16u, 16u}, std::pair{17u, 33u}}) {
    const PixelRegion regions[] = {{0, 0, width, height},
                                   {width - 1, 0, width, 1},
                                   {0, height - 1, 1, height},
                                   {3, 5, 4, 6},
                                   {width / 2, 1, width, height - 1}};
    for (const PixelRegion& r : regions) {
      SCOPED_TRACE(cat(width, "x", height, " ", region_text(r)));
      uint64_t met = 0;
      const uint64_t tiles = uint64_t((width + 15) / 16) * ((height + 15) / 16);
      for (uint64_t t = 0; t < tiles; ++t)
        met += region_meets_tile(r, width, height, t);
      EXPECT_EQ(met, tiles_met_by_pixels(r, width, height));
      for (uint32_t y = 0; y < height; ++y) {  // single rows of the pixel grid, y up
        const uint32_t row = height - 1 - y;
        EXPECT_EQ(region_meets_rows(r, height, y, 1), row >= r.y0 && row < r.y1) << y;
      }
    }
  }
}

TEST(Region, ProcessesShareTheRegionsTilesEvenly) {
  // One tile column of a 4-tile-wide image: dealing all tiles round-robin over 2 processes
  // would give every one of its tiles to the same process.
  const PixelRegion column{16, 0, 32, 64};
  for (uint32_t count : {2u, 3u}) {
    std::vector<int> tiles_of(count, 0);
    for (uint32_t p = 0; p < count; ++p) {
      TileShare share = region_share({p, count, nullptr}, column, 64, 64);
      for (uint64_t t = 0; t < 16; ++t)
        tiles_of[p] += share.owns(t) && region_meets_tile(column, 64, 64, t);
    }
    int total = 0, most = 0, least = 4;
    for (int n : tiles_of)
      total += n, most = std::max(most, n), least = std::min(least, n);
    EXPECT_EQ(total, 4) << count;
    EXPECT_LE(most - least, 1) << count;
  }
}

TEST(Region, ChecksSayWhatIsWrong) {
  EXPECT_TRUE(check_region({0, 0, 72, 52}, 72, 52).ok());
  auto empty = check_region({5, 5, 5, 9}, 72, 52);
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.error().find("5,5,5,9 is empty"), std::string::npos) << empty.error();
  auto past = check_region({0, 0, 73, 52}, 72, 52);
  ASSERT_FALSE(past.ok());
  EXPECT_NE(past.error().find("reaches past the 72x52 image"), std::string::npos) << past.error();
  EXPECT_FALSE(check_region({0, 0, 72, 53}, 72, 52).ok());
}

TEST(Region, FilmFilesKeepTheRegionAndRefuseADamagedOne) {
  std::string dir = testing::temp_dir();
  Film f;
  f.region = PixelRegion{1, 0, 3, 2};
  f.aovs = *parse_aov_list("depth");
  f.clear(4, 3);
  f.passes = 2;
  ASSERT_EQ(f.sum.size(), 2u * 2 * 3);  // the region's pixels alone
  for (std::size_t i = 0; i < f.sum.size(); ++i)
    f.sum[i] = 0.25 * double(i);
  for (std::size_t i = 0; i < f.aov_sum.size(); ++i)
    f.aov_sum[i] = 1.5 + double(i);
  ASSERT_TRUE(save_film(dir + "/r.film", f).ok());
  auto back = load_film(dir + "/r.film");
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->region, f.region);
  EXPECT_EQ(back->aov_sum, f.aov_sum);
  EXPECT_EQ(back->sum, f.sum);
  EXPECT_EQ(testing::read_file(dir + "/r.film").size(), 64u + 16 + 4 * 3 * 8 + 8 + 4 * 8);

  Film w = f;
  w.region.reset();
  w.clear(4, 3);
  ASSERT_TRUE(save_film(dir + "/w.film", w).ok());
  auto whole = load_film(dir + "/w.film");
  ASSERT_TRUE(whole.ok()) << whole.error();
  EXPECT_FALSE(whole->region);
  EXPECT_EQ(whole->sum.size(), 4u * 3 * 3);

  // x1 = 9 of a 4-wide film: the corners follow the 64-byte header.
  std::string bytes = testing::read_file(dir + "/r.film");
  ASSERT_EQ(bytes.substr(0, 7), "RLFILM3");
  bytes[64 + 8] = 9;
  testing::write_file(dir + "/bad.film", bytes);
  auto bad = load_film(dir + "/bad.film");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().find("1,0,9,2 reaches past the 4x3 image"), std::string::npos)
      << bad.error();
}

// Region films of the second format summed the whole image and named the region after the
// sums ("RGN1"); they are read as the region's pixels alone, so they resume as before.
TEST(Region, SecondFormatRegionFilmsAreCutToTheirRegionAsRead) {
  std::string dir = testing::temp_dir();
  Film whole;
  whole.aovs = *parse_aov_list("depth");
  whole.clear(4, 3);
  whole.passes = 1;
  for (std::size_t i = 0; i < whole.sum.size(); ++i)
    whole.sum[i] = double(i);
  for (std::size_t i = 0; i < whole.aov_sum.size(); ++i)
    whole.aov_sum[i] = 100.0 + double(i);
  ASSERT_TRUE(save_film(dir + "/w.film", whole).ok());
  std::string bytes = testing::read_file(dir + "/w.film");
  const std::size_t colour_end = 64 + 4 * 3 * 3 * 8;
  const uint32_t corners[4] = {1, 1, 3, 3};
  std::string region("RGN1");
  region.append(reinterpret_cast<const char*>(corners), sizeof corners);
  bytes.insert(colour_end, region);
  testing::write_file(dir + "/old.film", bytes);
  auto old = load_film(dir + "/old.film");
  ASSERT_TRUE(old.ok()) << old.error();
  ASSERT_EQ(old->region, (PixelRegion{1, 1, 3, 3}));
  // Pixel (x, y) of the image held sums 3·(4y + x) + k; the region's rows are y = 1, 2.
  const std::vector<double> expected = {15, 16, 17, 18, 19, 20, 27, 28, 29, 30, 31, 32};
  EXPECT_EQ(old->sum, expected);
  EXPECT_EQ(old->aov_sum, (std::vector<double>{105, 106, 109, 110}));
}

}  // namespace
}  // namespace raylane
