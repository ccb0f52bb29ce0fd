// Variants of the formats raylane reads that once came back wrong (docs/design.md, "Images in"): a
// grey PFM (`Pf`), a BMP stored top row first (negative height), a PFM whose scale is NaN.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "raylane/image/input_image.h"
#include "raylane/image/pfm.h"

namespace raylane {
namespace {

std::string le32(uint32_t v) {
  return {char(v), char(v >> 8), char(v >> 16), char(v >> 24)};
}

std::string floats(std::initializer_list<float> values) {
  std::string out;
  for (float v : values) {
    char b[4];
    std::memcpy(b, &v, 4);
    out.append(b, 4);
  }
  return out;
}

// Two rows of three grey values, bottom row first, little endian.
TEST(InputVariants, AGreyPfmIsReadAsThreeEqualChannels) {
  std::string pf = "Pf\n3 2\n-1.0\n" + floats({1, 2, 3, 4, 5, 6});
  auto img = decode_input_image(pf, "g.pfm");
  ASSERT_TRUE(img) << img.error();
  ASSERT_EQ(img->width, 3u);
  ASSERT_EQ(img->height, 2u);
  EXPECT_EQ(img->at(0, 1), glm::vec3(1, 1, 1));  // the bottom row comes first in the file
  EXPECT_EQ(img->at(2, 0), glm::vec3(6, 6, 6));
  auto truncated = decode_input_image("Pf\n3 2\n-1.0\n" + floats({1, 2, 3}), "g.pfm");
  EXPECT_FALSE(truncated);
}

TEST(InputVariants, APfmScaleMustBeAFiniteNumber) {
  for (std::string scale : {"nan", "-nan", "inf", "0"}) {
    auto img = decode_input_image("PF\n1 1\n" + scale + "\n" + floats({1, 2, 3}), "s.pfm");
    ASSERT_FALSE(img) << scale;
    EXPECT_NE(img.error().find("bad PFM scale"), std::string::npos) << img.error();
  }
}

// A 2×2 24-bit BMP whose height is −2: its first stored row is the top one (BITMAPINFOHEADER's
// biHeight < 0). Pixels are stored blue, green, red; rows padded to 4 bytes.
TEST(InputVariants, ATopDownBmpKeepsItsSizeAndRowOrder) {
  std::string pixels = std::string{0, 0, char(255), 0, char(255), 0, 0, 0} +  // top: red, green
                       std::string{char(255), 0, 0, char(255), char(255), char(255), 0, 0};
  std::string bmp = "BM" + le32(54 + uint32_t(pixels.size())) + le32(0) + le32(54);
  bmp += le32(40) + le32(2) + le32(uint32_t(-2)) + std::string{1, 0, 24, 0} + le32(0) +
         le32(uint32_t(pixels.size())) + le32(2835) + le32(2835) + le32(0) + le32(0) + pixels;
  auto info = probe_input_image(bmp, "t.bmp");
  ASSERT_TRUE(info) << info.error();
  EXPECT_EQ(info->height, 2u);
  auto img = decode_input_image(bmp, "t.bmp");
  ASSERT_TRUE(img) << img.error();
  EXPECT_EQ(img->at(0, 0), glm::vec3(1, 0, 0));  // red, top left
  EXPECT_EQ(img->at(1, 0), glm::vec3(0, 1, 0));
  EXPECT_EQ(img->at(0, 1), glm::vec3(0, 0, 1));
  EXPECT_EQ(img->at(1, 1), glm::vec3(1, 1, 1));
}

}  // namespace
}  // namespace raylane
