// Images: RGBE, PFM and PNG encodings, atomic writes, metrics.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "raylane/image/metrics.h"
#include "raylane/image/pfm.h"
#include "raylane/image/png.h"
#include "raylane/image/rgbe.h"
#include "raylane/image/write_image.h"
#include "support/paths.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;
using testing::temp_dir;

Image random_image(uint32_t w, uint32_t h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> e(-3, 4);  // 1e-3 .. 1e4
  Image img(w, h);
  for (float& v : img.rgb)
    v = std::pow(10.0f, e(rng));
  return img;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(Rgbe, KnownEncodings) {
  EXPECT_EQ(float_to_rgbe(1, 1, 1), (std::array<uint8_t, 4>{128, 128, 128, 129}));
  EXPECT_EQ(float_to_rgbe(0, 0, 0), (std::array<uint8_t, 4>{0, 0, 0, 0}));
  EXPECT_EQ(float_to_rgbe(-1, std::nanf(""), 0), (std::array<uint8_t, 4>{0, 0, 0, 0}));
  auto big = float_to_rgbe(INFINITY, 0, 0);
  EXPECT_EQ(big[3], 255);
  EXPECT_TRUE(std::isfinite(rgbe_to_float(big).x));
  EXPECT_EQ(rgbe_to_float({128, 64, 0, 129}), glm::vec3(1.0f, 0.5f, 0.0f));
}

// Each channel keeps 8 bits relative to the pixel's largest channel: truncation to the
// mantissa loses less than one step of 2^(e−8), i.e. < max·2^-7 (the mantissa of the largest
// channel is ≥ 128).
void expect_rgbe_close(const Image& a, const Image& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  for (std::size_t p = 0; p < a.rgb.size(); p += 3) {
    float m = std::max(a.rgb[p], std::max(a.rgb[p + 1], a.rgb[p + 2]));
    for (int k = 0; k < 3; ++k) {
      ASSERT_LE(a.rgb[p + k] - b.rgb[p + k], m * 0x1p-7f) << p;
      ASSERT_GE(a.rgb[p + k] - b.rgb[p + k], 0.0f) << p;  // truncation never rounds up
    }
  }
}

TEST(Rgbe, RoundTripAtFlatAndRleWidths) {
  for (uint32_t w : {1u, 7u, 8u, 100u, 32767u, 32768u}) {
    Image img = random_image(w, 3, w);
    std::string bytes = encode_rgbe(img, {"SAMPLES_PER_PIXEL=16"});
    auto back = decode_rgbe(bytes);
    ASSERT_TRUE(back) << w << ": " << back.error();
    expect_rgbe_close(img, back->image);
    EXPECT_EQ(back->metadata,
              (std::vector<std::string>{"SOFTWARE=raylane", "SAMPLES_PER_PIXEL=16"}));
  }
}

TEST(Rgbe, HeaderIsExactlyAsSpecified) {
  std::string bytes = encode_rgbe(Image(10, 2));
  EXPECT_EQ(bytes.substr(0, 63),
            "#?RADIANCE\nSOFTWARE=raylane\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 10\n");
}

TEST(Rgbe, RunLengthEncodingCompresses) {
  Image img(1000, 10);
  for (float& v : img.rgb)
    v = 0.25f;
  std::string bytes = encode_rgbe(img);
  EXPECT_LT(bytes.size(), 1000u);  // flat would be 40000 bytes of pixels
  auto back = decode_rgbe(bytes);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->image.at(999, 9), glm::vec3(0.25f, 0.25f, 0.25f));
}

// A header announcing a wide image over a few bytes used to size its row buffer (a GiB for
// 2^28 pixels) before reading a row; the announced rows must fit the bytes that follow.
TEST(Rgbe, AnnouncedSizeBeyondTheDataIsRefusedBeforeAllocating) {
  for (const char* res : {"-Y 1 +X 268435456", "-Y 16384 +X 16384", "-Y 2 +X 100"}) {
    auto r = decode_rgbe(std::string("#?RADIANCE\n\n") + res + "\n\2\2\0\144abcd");
    ASSERT_FALSE(r) << res;
    EXPECT_NE(r.error().find("the header announces"), std::string::npos) << r.error();
  }
}

TEST(Rgbe, HostileInputIsAnError) {
  std::string good = encode_rgbe(random_image(64, 4, 1));
  for (std::size_t cut : {0ul, 5ul, 40ul, good.size() / 2, good.size() - 1})
    EXPECT_FALSE(decode_rgbe(good.substr(0, cut))) << cut;
  EXPECT_FALSE(decode_rgbe("P6\n1 1\n255\nabc"));
  EXPECT_FALSE(decode_rgbe("#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n\1\1\1\1"));
  EXPECT_FALSE(decode_rgbe("#?RADIANCE\n\n+Y 1 +X 1\n\1\1\1\1"));
  EXPECT_FALSE(decode_rgbe("#?RADIANCE\n\n-Y 1000000000 +X 1000000000\n"));
  // A declared size far beyond the data: an error without allocating the declared size.
  EXPECT_FALSE(decode_rgbe("#?RADIANCE\n\n-Y 16384 +X 16384\n\2\2\x40\0\x80"));
  // A run that overflows the scanline.
  std::string bad = "#?RADIANCE\n\n-Y 1 +X 8\n";
  bad += std::string("\2\2\0\x08\xff\x01", 6);
  EXPECT_FALSE(decode_rgbe(bad));
}

TEST(Pfm, BottomRowFirstAndBitExact) {
  Image img(2, 2);
  img.set(0, 0, {1, 2, 3});  // top-left
  img.set(0, 1, {4, 5, 6});  // bottom-left
  std::string bytes = encode_pfm(img);
  ASSERT_EQ(bytes.substr(0, 12), "PF\n2 2\n-1.0\n");
  float first;
  std::memcpy(&first, bytes.data() + 12, 4);
  EXPECT_EQ(first, 4.0f);  // the file starts with the bottom row
  Image r = random_image(17, 5, 3);
  auto back = decode_pfm(encode_pfm(r));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->rgb, r.rgb);
  EXPECT_FALSE(decode_pfm(encode_pfm(r).substr(0, 100)));
  EXPECT_FALSE(decode_pfm("PF\n100000 100000\n-1\n"));
}

TEST(Png, SrgbEncoding) {
  EXPECT_EQ(srgb_encode_8bit(0), 0);
  EXPECT_EQ(srgb_encode_8bit(1), 255);
  EXPECT_EQ(srgb_encode_8bit(0.5f), 188);
  EXPECT_EQ(srgb_encode_8bit(7), 255);
  EXPECT_EQ(srgb_encode_8bit(-1), 0);
  EXPECT_EQ(srgb_encode_8bit(std::nanf("")), 0);
}

std::vector<uint8_t> decode_png_rgb(const std::string& path, uint32_t& w, uint32_t& h) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  std::vector<uint8_t> px;
  if (!png_image_begin_read_from_file(&img, path.c_str())) return px;
  img.format = PNG_FORMAT_RGB;
  px.resize(PNG_IMAGE_SIZE(img));
  png_image_finish_read(&img, nullptr, px.data(), 0, nullptr);
  w = img.width, h = img.height;
  return px;
}

TEST(Png, WritesDecodableSrgbWithExposure) {
  std::string dir = temp_dir();
  Image img(2, 1);
  img.set(0, 0, {0.25f, 0.5f, 1.0f});
  img.set(1, 0, {0, 2, 0.25f});
  ASSERT_TRUE(write_image(dir + "/a.png", img));
  WriteOptions brighter;
  brighter.exposure = 1;
  ASSERT_TRUE(write_image(dir + "/b.png", img, brighter));
  EXPECT_EQ(read_file(dir + "/a.png").substr(0, 8), "\x89PNG\r\n\x1a\n");
  uint32_t w = 0, h = 0;
  auto a = decode_png_rgb(dir + "/a.png", w, h);
  ASSERT_EQ(a.size(), 6u);
  EXPECT_EQ((std::vector<int>(a.begin(), a.end())), (std::vector<int>{137, 188, 255, 0, 255, 137}));
  auto b = decode_png_rgb(dir + "/b.png", w, h);
  EXPECT_EQ((std::vector<int>(b.begin(), b.end())), (std::vector<int>{188, 255, 255, 0, 255, 188}));
}

TEST(WriteImage, FormatFromExtension) {
  EXPECT_EQ(*format_from_path("a.hdr"), ImageFormat::kHdr);
  EXPECT_EQ(*format_from_path("dir.x/A.HDR"), ImageFormat::kHdr);
  EXPECT_EQ(*format_from_path("a.pfm"), ImageFormat::kPfm);
  EXPECT_EQ(*format_from_path("a.png"), ImageFormat::kPng);
  EXPECT_FALSE(format_from_path("a.jpg"));
  EXPECT_FALSE(format_from_path("hdr"));
}

bool no_temp_files(const std::string& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string()[0] == '.') return false;
  return true;
}

TEST(WriteImage, RoundTripThroughFiles) {
  std::string dir = temp_dir();
  Image img = random_image(33, 9, 5);
  ASSERT_TRUE(write_image(dir + "/x.hdr", img));
  ASSERT_TRUE(write_image(dir + "/x.pfm", img));
  auto hdr = read_image(dir + "/x.hdr");
  auto pfm = read_image(dir + "/x.pfm");
  ASSERT_TRUE(hdr && pfm);
  expect_rgbe_close(img, *hdr);
  EXPECT_EQ(pfm->rgb, img.rgb);
  EXPECT_TRUE(no_temp_files(dir));
}

TEST(WriteImage, FailuresCreateNothingAndKeepExistingFiles) {
  std::string dir = temp_dir();
  Image img(4, 4);
  EXPECT_FALSE(write_image(dir + "/missing/x.hdr", img));
  EXPECT_FALSE(fs::exists(dir + "/missing"));
  Status missing = check_writable(dir + "/missing/x.hdr");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().find(": no such folder"), std::string::npos) << missing.error();
  std::ofstream(dir + "/plain") << "a file, not a folder";
  Status not_folder = check_writable(dir + "/plain/x.hdr");
  ASSERT_FALSE(not_folder);
  EXPECT_EQ(not_folder.error(), "'" + dir + "/plain' is not a folder") << not_folder.error();
  fs::create_directory(dir + "/taken.hdr");
  EXPECT_FALSE(write_image(dir + "/taken.hdr", img));
  EXPECT_TRUE(fs::is_directory(dir + "/taken.hdr"));
  std::ofstream(dir + "/keep.hdr") << "precious";
  EXPECT_FALSE(write_image(dir + "/keep.hdr.jpg", img));  // unknown format: nothing written
  EXPECT_EQ(read_file(dir + "/keep.hdr"), "precious");
  EXPECT_TRUE(no_temp_files(dir));
  EXPECT_TRUE(check_writable(dir + "/new.hdr"));
  EXPECT_FALSE(fs::exists(dir + "/new.hdr"));
}

TEST(Metrics, KnownDifferences) {
  Image a(2, 1), b(2, 1);
  b.set(0, 0, {1, 1, 1});
  auto d = compare(a, b);
  ASSERT_TRUE(d);
  EXPECT_DOUBLE_EQ(d->rmse, std::sqrt(0.5));
  EXPECT_DOUBLE_EQ(d->mean_abs, 0.5);
  EXPECT_DOUBLE_EQ(d->max_abs, 1.0);
  EXPECT_DOUBLE_EQ(d->rel_mse, 0.5 / 1.01);
  EXPECT_FALSE(compare(a, Image(1, 2)));
  EXPECT_EQ(mean(b), glm::dvec3(0.5, 0.5, 0.5));
}

}  // namespace
}  // namespace raylane
