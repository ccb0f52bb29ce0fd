// Texture and environment images in (image/input_image.h): every format, sRGB decoding, the
// orientation of rows, and hostile headers refused before anything is decoded.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "raylane/image/input_image.h"
#include "raylane/image/pfm.h"
#include "raylane/image/png.h"
#include "raylane/image/rgbe.h"
#include "support/paths.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Writes an 8-bit sRGB PNG of `img` (exposure 0) and returns its bytes.
std::string png_bytes(const Image& img) {
  std::string path = testing::temp_dir() + "/t.png";
  std::FILE* f = std::fopen(path.c_str(), "wb");
  EXPECT_TRUE(write_png(f, img, 0));
  std::fclose(f);
  return slurp(path);
}

std::string le32(uint32_t v) {
  return {char(v), char(v >> 8), char(v >> 16), char(v >> 24)};
}
std::string be32(uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

// A PNG signature and an IHDR chunk announcing w×h RGB 8-bit, and nothing else (stb_image does
// not check CRCs, so the CRC is left 0).
std::string png_header_only(uint32_t w, uint32_t h) {
  std::string ihdr = be32(w) + be32(h) + std::string{8, 2, 0, 0, 0};
  return std::string("\x89PNG\r\n\x1a\n", 8) + be32(13) + "IHDR" + ihdr + be32(0);
}

TEST(SrgbToLinear, MatchesTheStandardAtKnownPoints) {
  EXPECT_EQ(srgb_to_linear(0), 0);
  EXPECT_EQ(srgb_to_linear(1), 1);
  EXPECT_NEAR(srgb_to_linear(0.5), 0.214041140, 1e-9);
  EXPECT_NEAR(srgb_to_linear(0.04045), 0.04045 / 12.92, 1e-15);  // the linear segment's end
  EXPECT_NEAR(srgb_to_linear(0.2), 0.033104767, 1e-9);
}

TEST(InputImage, PngIsSrgbDecodedWithTheTopRowFirst) {
  Image img(3, 2);
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 3; ++x)
      img.set(x, y, {x / 2.0f, y * 1.0f, 0.5f});
  auto back = decode_input_image(png_bytes(img), "t.png");
  ASSERT_TRUE(back) << back.error();
  ASSERT_EQ(back->width, 3u);
  ASSERT_EQ(back->height, 2u);
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 3; ++x) {
      glm::vec3 c = back->at(x, y);
      // write_png rounded each channel to 8 bits; decoding must undo exactly that code.
      EXPECT_EQ(c.x, float(srgb_to_linear(srgb_encode_8bit(x / 2.0f) / 255.0)));
      EXPECT_EQ(c.y, float(srgb_to_linear(srgb_encode_8bit(float(y)) / 255.0)));
      EXPECT_EQ(c.z, float(srgb_to_linear(srgb_encode_8bit(0.5f) / 255.0)));
    }
  EXPECT_EQ(back->at(0, 1).y, 1.0f);  // row 1 is the bottom: y = 1 was written there
}

TEST(InputImage, HdrAndPfmAreLinear) {
  Image img(9, 3);  // 9 wide: RLE scanlines in the HDR file
  for (uint32_t y = 0; y < 3; ++y)
    for (uint32_t x = 0; x < 9; ++x)
      img.set(x, y,
              {std::pow(10.0f, float(x) - 4), std::pow(10.0f, float(x) - 4) * (1.5f + float(y)),
               std::pow(10.0f, float(x) - 4) * 0.75f});
  auto pfm = decode_input_image(encode_pfm(img), "t.pfm");
  ASSERT_TRUE(pfm) << pfm.error();
  EXPECT_EQ(pfm->rgb, img.rgb);
  auto hdr = decode_input_image(encode_rgbe(img), "t.hdr");
  ASSERT_TRUE(hdr) << hdr.error();
  // RGBE keeps 8 bits of mantissa under the pixel's shared exponent: an error of at most
  // 1/128 of the pixel's largest channel.
  for (std::size_t i = 0; i < img.rgb.size(); ++i) {
    float largest = img.rgb[i / 3 * 3 + 1];
    EXPECT_NEAR(hdr->rgb[i], img.rgb[i], largest / 128) << i;
  }
}

TEST(InputImage, PngJpegTgaAndBmpOfTheAssimpModelsDecode) {
  const std::string models = RAYLANE_ASSIMP_MODELS;
  if (!fs::exists(models)) GTEST_SKIP() << "assimp-testmodels is not installed";
  int decoded = 0;
  for (const auto& e : fs::recursive_directory_iterator(models)) {
    std::string ext = e.path().extension().string();
    for (char& c : ext)
      c = char(std::tolower(c));
    if (ext != ".png" && ext != ".jpg" && ext != ".tga" && ext != ".bmp") continue;
    auto img = read_input_image(e.path().string());
    if (!img) {
      ADD_FAILURE() << img.error();
      continue;
    }
    EXPECT_GT(img->width, 0u);
    ++decoded;
  }
  EXPECT_GE(decoded, 60);  // 45 PNG, TGA and BMP and 22 JPEG images in Debian 12's package
}

TEST(InputImage, NegativeOrNonFinitePixelsAreAnError) {
  for (float bad :
       {-1.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    Image img(2, 2);
    img.set(1, 0, {0.5f, bad, 0});
    auto r = decode_input_image(encode_pfm(img), "t.pfm");
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().find("pixel (1, 0)"), std::string::npos) << r.error();
  }
}

TEST(InputImage, AnnouncedSizeBeyondWhatTheFileHoldsIsRefusedBeforeDecoding) {
  auto r = probe_input_image(png_header_only(16000, 16000), "big.png");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("more than"), std::string::npos) << r.error();
  auto limit = probe_input_image("PF\n70000 70000\n-1\n", "huge.pfm");
  ASSERT_FALSE(limit);
  EXPECT_NE(limit.error().find("limit"), std::string::npos) << limit.error();
  // A size the file could hold passes the header check and fails in decoding (no IDAT).
  auto small = decode_input_image(png_header_only(64, 64), "small.png");
  ASSERT_FALSE(small);
  EXPECT_NE(small.error().find("cannot decode"), std::string::npos) << small.error();
}

TEST(InputImage, AChunkAnnouncingGigabytesFailsWithinTheBudget) {
  // IDAT announcing 2^31 − 1 bytes after a valid 8×8 header: stb_image would grow its buffer
  // to that size before reading; the budget refuses it.
  std::string b = png_header_only(8, 8) + be32(0x7fffffff) + "IDAT" + std::string(64, 'x');
  auto r = decode_input_image(b, "chunk.png");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("outofmem"), std::string::npos) << r.error();  // not "outofdata"
}

TEST(InputImage, TruncatedFilesAreErrors) {
  Image img(16, 16);
  for (uint32_t i = 0; i < 16; ++i)
    img.set(i, i, {1, 0.5f, 0.25f});
  std::string full = png_bytes(img);
  for (std::size_t keep :
       {std::size_t(0), std::size_t(8), std::size_t(30), full.size() / 2, full.size() - 13}) {
    auto r = decode_input_image(full.substr(0, keep), "t.png");
    EXPECT_FALSE(r) << keep;
  }
  std::string bmp = "BM" + le32(70) + le32(0) + le32(54) + le32(40) + le32(4000) + le32(4000);
  EXPECT_FALSE(decode_input_image(bmp, "t.bmp"));
}

TEST(InputImage, UnknownFormatsAndEmptyFilesAreErrorsSayingWhatIsRead) {
  auto r = decode_input_image("P6\n1 1\n255\nabc", "t.ppm");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("PNG, JPEG, TGA, BMP"), std::string::npos) << r.error();
  auto empty = decode_input_image("", "t.png");
  ASSERT_FALSE(empty);
  EXPECT_NE(empty.error().find("empty"), std::string::npos);
}

TEST(InputImage, FileErrorsNameThePath) {
  std::string dir = testing::temp_dir();
  auto missing = read_input_image(dir + "/none.png");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().find("none.png"), std::string::npos);
  auto directory = read_input_image(dir);
  ASSERT_FALSE(directory);
  EXPECT_NE(directory.error().find("directory"), std::string::npos) << directory.error();
}

}  // namespace
}  // namespace raylane
