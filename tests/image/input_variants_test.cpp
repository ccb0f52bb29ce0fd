// Variants of the formats raylane reads that once came back wrong (docs/design.md, "Images in"): a
// grey PFM (`Pf`), a BMP stored top row first (negative height), a PFM whose scale is NaN, palette
// BMPs whose indices point past their palette.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

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

// A palette BMP (BITMAPINFOHEADER) of `bits` a pixel with the given palette entries (blue,
// green, red each) and rows of stored bytes, each row already padded to 4 bytes.
std::string palette_bmp(uint32_t width, uint32_t height, uint16_t bits,
                        const std::vector<std::string>& palette, const std::string& rows) {
  std::string pal;
  for (const std::string& bgr : palette)
    pal += bgr + std::string(1, '\0');
  const uint32_t offset = 54 + uint32_t(pal.size());
  std::string bmp = "BM" + le32(offset + uint32_t(rows.size())) + le32(0) + le32(offset);
  bmp += le32(40) + le32(width) + le32(height) + std::string{1, 0, char(bits), 0} + le32(0) +
         le32(uint32_t(rows.size())) + le32(2835) + le32(2835) + le32(0) + le32(0);
  return bmp + pal + rows;
}

const std::string kRed{0, 0, char(255)}, kBlue{char(255), 0, 0};

// Indices inside a two-entry palette decode; the same file with one index past the palette is
// refused (stb would read that entry from its uninitialised stack palette, fuzz_image found
// two decodes of such a file that differed).
TEST(InputVariants, APaletteBmpWithAnIndexPastItsPaletteIsRefused) {
  const std::string good_rows =
      std::string{0, 1, 1, 0} + std::string{1, 0, 0, 0};  // 3 wide, 2 high
  auto img = decode_input_image(palette_bmp(3, 2, 8, {kRed, kBlue}, good_rows), "p.bmp");
  ASSERT_TRUE(img) << img.error();
  EXPECT_EQ(img->at(0, 1), glm::vec3(1, 0, 0));  // the bottom row comes first: index 0, red
  EXPECT_EQ(img->at(1, 1), glm::vec3(0, 0, 1));
  EXPECT_EQ(img->at(0, 0), glm::vec3(0, 0, 1));
  const std::string bad_rows = std::string{0, 1, 1, 0} + std::string{1, 0, 7, 0};
  auto bad = decode_input_image(palette_bmp(3, 2, 8, {kRed, kBlue}, bad_rows), "p.bmp");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().find("expected palette indices below the palette's 2 entries, found "
                             "index 7"),
            std::string::npos)
      << bad.error();
  // The padding after a row's last index is not a pixel: a 7 there is not looked up.
  const std::string padded = std::string{0, 1, 1, 7} + std::string{1, 0, 0, 7};
  EXPECT_TRUE(decode_input_image(palette_bmp(3, 2, 8, {kRed, kBlue}, padded), "p.bmp"));
}

// A palette BMP whose pixels' offset points into its own header: stb computes a negative
// palette size, reads no palette and looks every pixel up in its uninitialised one (fuzz_image
// found two decodes of such a file that differed). It is refused, with the offset named.
TEST(InputVariants, APaletteBmpWhosePixelsStartInsideItsHeaderIsRefused) {
  const std::string rows = std::string{0, 1, 1, 0} + std::string{1, 0, 0, 0};
  for (uint32_t offset : {50u, 53u, 40u}) {
    std::string bmp = palette_bmp(3, 2, 8, {kRed, kBlue}, rows);
    bmp.replace(10, 4, le32(offset));
    auto bad = decode_input_image(bmp, "p.bmp");
    ASSERT_FALSE(bad) << offset;
    EXPECT_NE(bad.error().find("found the pixels' offset " + std::to_string(offset) +
                               " inside the 40-byte header"),
              std::string::npos)
        << bad.error();
  }
}

// The same cut off after its bit count (fuzz_image's find): stb reads the rest of the header
// as zeros and decodes the 2×2 pixels from its uninitialised palette. Refused alike.
TEST(InputVariants, APaletteBmpCutOffInItsHeaderIsRefused) {
  std::string bmp = palette_bmp(2, 2, 8, {kRed, kBlue}, std::string(8, '\0'));
  bmp.replace(10, 4, le32(50));
  bmp.resize(30);
  auto bad = decode_input_image(bmp, "p.bmp");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().find("found the pixels' offset 50 inside the 40-byte header"),
            std::string::npos)
      << bad.error();
}

// 1- and 4-bit rows: a one-entry palette with a set bit, a two-entry one with a nibble of 2.
TEST(InputVariants, OneAndFourBitBmpsAreCheckedIndexByIndex) {
  const std::string one_bit_ok = std::string{char(0x00), 0, 0, 0};
  EXPECT_TRUE(decode_input_image(palette_bmp(8, 1, 1, {kRed}, one_bit_ok), "p.bmp"));
  const std::string one_bit_bad = std::string{char(0x01), 0, 0, 0};  // the 8th pixel is 1
  EXPECT_FALSE(decode_input_image(palette_bmp(8, 1, 1, {kRed}, one_bit_bad), "p.bmp"));
  // 7 pixels wide: the low bit of the byte is not a pixel and is not looked up.
  EXPECT_TRUE(decode_input_image(palette_bmp(7, 1, 1, {kRed}, one_bit_bad), "p.bmp"));
  const std::string nibbles_ok = std::string{char(0x01), char(0x10), 0, 0};
  EXPECT_TRUE(decode_input_image(palette_bmp(3, 1, 4, {kRed, kBlue}, nibbles_ok), "p.bmp"));
  const std::string nibbles_bad = std::string{char(0x01), char(0x12), 0, 0};  // 4th pixel: 2
  EXPECT_TRUE(decode_input_image(palette_bmp(3, 1, 4, {kRed, kBlue}, nibbles_bad), "p.bmp"));
  EXPECT_FALSE(decode_input_image(palette_bmp(4, 1, 4, {kRed, kBlue}, nibbles_bad), "p.bmp"));
}

}  // namespace
}  // namespace raylane
