// Texel storage (image/texels.h): each file kind is kept in its compact form, and every form
// decodes to exactly the floats the float reader returns, so renders do not change with it.
#include "raylane/image/texels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>

#include "raylane/image/exr.h"
#include "raylane/image/input_image.h"
#include "raylane/image/png.h"
#include "raylane/image/rgbe.h"
#include "support/paths.h"

namespace raylane {
namespace {

// Colours over the decades an HDR sky spans, and over [0, 1] for 8-bit files.
Image random_image(uint32_t w, uint32_t h, float max, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> d(0.0f, 1.0f);
  Image img(w, h);
  for (float& c : img.rgb)
    c = max > 1 ? std::pow(max, d(rng)) - 1 : d(rng);
  return img;
}

template <class Write>
std::string file_bytes(Write write) {
  std::string path = testing::temp_dir() + "/t.bin";
  std::FILE* f = std::fopen(path.c_str(), "wb");
  EXPECT_TRUE(write(f));
  std::fclose(f);
  return testing::read_file(path);
}

void expect_same_floats(const TexelImage& t, const Image& img) {
  ASSERT_EQ(t.width, img.width);
  ASSERT_EQ(t.height, img.height);
  EXPECT_EQ(to_float_image(t).rgb, img.rgb);
}

TEST(Half, EveryNonNegativeFiniteHalfRoundTripsExactly) {
  for (uint32_t h = 0; h < 0x7c00u; ++h) {  // +0 up to the largest finite half
    uint16_t back = 0;
    float f = half_to_float(uint16_t(h));
    ASSERT_TRUE(float_to_half_exactly(f, back)) << h;
    ASSERT_EQ(back, h) << f;
  }
  EXPECT_EQ(half_to_float(0x3c00), 1.0f);
  EXPECT_EQ(half_to_float(0x0001), 0x1p-24f);
  EXPECT_EQ(half_to_float(0x7bff), 65504.0f);
}

TEST(Half, FloatsAHalfCannotHoldAreRefused) {
  uint16_t h = 0;
  EXPECT_FALSE(float_to_half_exactly(0.1f, h));      // 24 mantissa bits
  EXPECT_FALSE(float_to_half_exactly(65536.0f, h));  // beyond the largest half
  EXPECT_FALSE(float_to_half_exactly(0x1p-25f, h));  // below the smallest subnormal
  EXPECT_FALSE(float_to_half_exactly(1.0f + 0x1p-11f, h));
  EXPECT_FALSE(float_to_half_exactly(NAN, h));
  EXPECT_FALSE(float_to_half_exactly(-1.0f, h));
  EXPECT_TRUE(float_to_half_exactly(1.0f + 0x1p-10f, h));
  EXPECT_EQ(h, 0x3c01);
}

TEST(Texels, An8BitPngIsKeptAsItsBytesAndDecodesAsTheFloatReaderDoes) {
  Image src = random_image(37, 23, 1, 1);
  std::string png = file_bytes([&](std::FILE* f) { return bool(write_png(f, src, 0)); });
  auto floats = decode_input_image(png, "t.png");
  auto texels = decode_input_texels(png, "t.png");
  ASSERT_TRUE(floats) << floats.error();
  ASSERT_TRUE(texels) << texels.error();
  EXPECT_EQ(texels->format, TexelFormat::kSrgb8);
  EXPECT_EQ(texels->bytes(), 37u * 23 * 4);
  expect_same_floats(*texels, *floats);
}

TEST(Texels, ARadianceFileIsKeptAsItsRgbeBytesAndDecodesAsTheFloatReaderDoes) {
  Image src = random_image(64, 9, 1e5f, 2);
  src.set(3, 4, glm::vec3(0, 0, 0));
  src.set(5, 4, glm::vec3(1e-38f, 0, 0));  // an exponent byte below 10: a subnormal scale
  std::string hdr = encode_rgbe(src);
  auto floats = decode_input_image(hdr, "t.hdr");
  auto texels = decode_input_texels(hdr, "t.hdr");
  ASSERT_TRUE(floats) << floats.error();
  ASSERT_TRUE(texels) << texels.error();
  EXPECT_EQ(texels->format, TexelFormat::kRgbe);
  EXPECT_EQ(texels->bytes(), 64u * 9 * 4);
  expect_same_floats(*texels, *floats);
}

TEST(Texels, AHalfExrIsKeptInHalvesAndAFloatOneInFloats) {
  Image src = random_image(16, 8, 1e3f, 3);
  ExrWriteOptions half;
  half.half = true;
  std::string h = file_bytes([&](std::FILE* f) { return bool(write_exr(f, src, {}, half)); });
  std::string full = file_bytes([&](std::FILE* f) { return bool(write_exr(f, src)); });
  for (const auto& [bytes, format] :
       {std::pair{h, TexelFormat::kHalf}, std::pair{full, TexelFormat::kFloat}}) {
    auto floats = decode_input_image(bytes, "t.exr");
    auto texels = decode_input_texels(bytes, "t.exr");
    ASSERT_TRUE(floats) << floats.error();
    ASSERT_TRUE(texels) << texels.error();
    EXPECT_EQ(texels->format, format);
    EXPECT_EQ(texels->bytes(), 16u * 8 * texel_bytes(format));
    expect_same_floats(*texels, *floats);
  }
}

// The asset of the report: a 4096² 8-bit texture, kept in 64 MiB (it took 192 as floats).
// A truncated uncompressed TGA (2050x2, 14 bytes of pixels): stb ignores the short read of a
// row, so its rows were whatever the heap held, and the float reader and the texels disagreed
// (found by the image fuzzer). Rows never read are black, and every decode is the same.
TEST(Texels, ATruncatedTgaDecodesTheSameEveryTime) {
  const unsigned char file[] = {0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x08, 0x00, 0x00, 0x00,
                                0x00, 0x00, 0x02, 0x08, 0x02, 0x00, 0x18, 0x28, 0x5a, 0x5a,
                                0x00, 0xa0, 0x00, 0xc0, 0x50, 0x78, 0x5a, 0x78, 0x50, 0x5a};
  const std::string_view bytes(reinterpret_cast<const char*>(file), sizeof file);
  // Dirty the heap with the sizes the decoder allocates, so leftovers would show.
  for (int i = 0; i < 4; ++i) {
    std::vector<unsigned char> junk(2050 * 2 * 3, 0xAB);
    volatile unsigned char sink = junk[std::size_t(i)];
    (void)sink;
  }
  auto image = decode_input_image(bytes, "input.tga", kDefaultImageMemory);
  ASSERT_TRUE(image.ok()) << image.error();
  ASSERT_EQ(image->width, 2050u);
  auto texels = decode_input_texels(bytes, "input.tga", kDefaultImageMemory);
  ASSERT_TRUE(texels.ok()) << texels.error();
  EXPECT_EQ(to_float_image(*texels).rgb, image->rgb);
  std::size_t black = 0;
  for (std::size_t i = 30; i < image->rgb.size(); ++i)
    black += image->rgb[i] == 0.0f;
  EXPECT_EQ(black, image->rgb.size() - 30);  // nothing past the file's bytes but black
}

TEST(Texels, A4kPngTextureTakesFourBytesATexel) {
  Image src(4096, 4096);
  for (uint32_t y = 0; y < 4096; ++y)
    for (uint32_t x = 0; x < 4096; ++x)
      src.set(x, y, glm::vec3(x / 4096.0f, y / 4096.0f, 0.5f));
  std::string png = file_bytes([&](std::FILE* f) { return bool(write_png(f, src, 0)); });
  src = Image();
  InputImageInfo info{InputFormat::kPng, 4096, 4096, 3};
  EXPECT_EQ(stored_texel_bytes(info), uint64_t(64) << 20);
  auto texels = decode_input_texels(png, "t.png", decode_texels_bytes(info, png.size()));
  ASSERT_TRUE(texels) << texels.error();
  EXPECT_EQ(texels->bytes(), uint64_t(64) << 20);
  EXPECT_EQ(texels->at(4095, 0).x, srgb8_table()[255]);
}

}  // namespace
}  // namespace raylane
