// Hostile images (issue 34): a decompression bomb is refused from its header before it is
// decoded, a file is read whole only after its first bytes are an image's, `info` reads
// headers only, and an OpenEXR luminance-chroma file reads as its colour, never as zeros.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <string>

#include "raylane/core/alloc_budget.h"
#include "raylane/image/exr.h"
#include "raylane/image/input_image.h"
#include "support/hostile_files.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::temp_dir;

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// A file of `bytes` that starts with `start` and is zeros after it, without the zeros on disk.
void write_sparse(const std::string& path, const std::string& start, off_t bytes) {
  write_file(path, start);
  ASSERT_EQ(::truncate(path.c_str(), bytes), 0);
}

TEST(ImageMemory, APngBombIsRefusedFromItsHeaderBeforeDecoding) {
  std::string bomb = testing::png_zero_bomb(8192, 8192);
  EXPECT_LT(bomb.size(), 60000u);  // 64 Mi samples in 53 KB: the per-byte bound lets it through
  AllocBudget budget(1 << 20);
  auto img = decode_input_image(bomb, "bomb.png");
  ASSERT_FALSE(img);
  EXPECT_NE(img.error().find("decoding its 8192x8192 pixels takes 1.2 GiB; the image memory "
                             "left is 192.0 MiB (--image-memory MIB raises it)"),
            std::string::npos)
      << img.error();
  EXPECT_LT(budget.peak(), 1u << 20);
}

// The same construction at a size within the budget is a valid PNG that decodes to black, and
// the budget the caller has left decides.
TEST(ImageMemory, TheBudgetLeftDecidesNotTheFileSize) {
  std::string small = testing::png_zero_bomb(1000, 700);
  auto img = decode_input_image(small, "small.png");
  ASSERT_TRUE(img) << img.error();
  EXPECT_EQ(img->width, 1000u);
  EXPECT_EQ(img->height, 700u);
  for (float v : img->rgb)
    ASSERT_EQ(v, 0.0f);
  uint64_t needed = decode_bytes({InputFormat::kPng, 1000, 700, 1}, small.size());
  EXPECT_TRUE(decode_input_image(small, "small.png", needed));
  auto refused = decode_input_image(small, "small.png", needed - 1);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().find("--image-memory"), std::string::npos) << refused.error();
}

// 300 MiB that are no image are refused after their first bytes; 300 MiB that start like a PNG
// are refused by their length, before they are read.
TEST(ImageMemory, AFileIsReadWholeOnlyAfterItsMagicBytes) {
  std::string dir = temp_dir();
  write_sparse(dir + "/zeros.png", "", off_t(300) << 20);
  write_sparse(dir + "/long.png", testing::png_zero_bomb(16, 16), off_t(300) << 20);
  AllocBudget budget(1 << 20);
  auto zeros = read_input_image(dir + "/zeros.png");
  ASSERT_FALSE(zeros);
  EXPECT_NE(zeros.error().find("zeros.png: not an image raylane reads"), std::string::npos)
      << zeros.error();
  auto info = read_input_image_info(dir + "/zeros.png");
  EXPECT_FALSE(info);
  auto longer = read_input_image(dir + "/long.png");
  ASSERT_FALSE(longer);
  EXPECT_NE(longer.error().find("reading the file takes 300.0 MiB; the image memory left is "
                                "192.0 MiB"),
            std::string::npos)
      << longer.error();
  EXPECT_LT(budget.peak(), 1u << 20);
}

// `raylane info` reads headers: the bomb's size, and a Radiance file's, without their pixels.
TEST(ImageMemory, InfoReadsOnlyTheHeader) {
  std::string dir = temp_dir();
  write_file(dir + "/bomb.png", testing::png_zero_bomb(8192, 8192));
  // 4 MiB can hold 9000x6000 run-length pixels; their rows are not read (here: zeros).
  write_sparse(dir + "/big.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 6000 +X 9000\n",
               off_t(4) << 20);
  AllocBudget budget(1 << 20);
  auto png = read_input_image_info(dir + "/bomb.png");
  ASSERT_TRUE(png) << png.error();
  EXPECT_EQ(png->width, 8192u);
  auto hdr = read_input_image_info(dir + "/big.hdr");
  ASSERT_TRUE(hdr) << hdr.error();
  EXPECT_EQ(hdr->width, 9000u);
  EXPECT_EQ(hdr->height, 6000u);
  EXPECT_LT(budget.peak(), 1u << 20);
}

// Y, RY, BY (chroma subsampled 2×2) as OpenEXR's RGBA interface writes them, at half
// precision. Grey has no chroma, so Y's rounding to half (2^-11 relative) and the float
// conversions to and from it stand between a pixel and its value: 2^-10 bounds them. A constant
// colour's chroma is the same in every 2×2 block, so subsampling loses nothing; R = Y·(RY + 1)
// and B likewise, G from all three, each a few half roundings (2^-11 each): 1 % bounds them.
TEST(ExrLuminanceChroma, ReadsAsItsColourNotZeros) {
  auto grey = [](int x, int y) {
    float v = 0.05f + 0.01f * float(x + 3 * y);
    return glm::vec3(v, v, v);
  };
  auto bytes = testing::exr_luminance_chroma(16, 6, grey);
  auto info = probe_exr(bytes);
  ASSERT_TRUE(info) << info.error();
  EXPECT_TRUE(info->has_y);
  auto img = decode_input_image(bytes, "yc.exr");
  ASSERT_TRUE(img) << img.error();
  ASSERT_EQ(img->width, 16u);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 16; ++x) {
      glm::vec3 want = grey(x, y), got = img->at(uint32_t(x), uint32_t(y));
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(got[k], want[k], std::ldexp(want[k], -10)) << x << "," << y;
    }
  auto colour = [](int, int) { return glm::vec3(0.8f, 0.4f, 0.2f); };
  auto coloured = decode_exr(testing::exr_luminance_chroma(10, 4, colour));
  ASSERT_TRUE(coloured) << coloured.error();
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 10; ++x)
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(coloured->at(x, y)[k], colour(0, 0)[k], 0.01 * colour(0, 0)[k]);
  // A data window that does not start at (0, 0), here at negative x and y: the same pixels (UBSan
  // found the frame buffer's shifted address computed by pointer arithmetic past the rows).
  auto shifted = decode_exr(testing::exr_luminance_chroma(10, 4, colour, -8, -4));
  ASSERT_TRUE(shifted) << shifted.error();
  ASSERT_EQ(shifted->width, 10u);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 10; ++x)
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(shifted->at(x, y)[k], colour(0, 0)[k], 0.01 * colour(0, 0)[k]);
  // A layer of such a file is refused by name, never read as zeros.
  auto layer = decode_exr_layer(bytes, "");
  ASSERT_FALSE(layer);
  EXPECT_NE(layer.error().find("is subsampled"), std::string::npos) << layer.error();
}

}  // namespace
}  // namespace raylane
