// `raylane diff`: the numbers of two images and the exit status scripts rely on.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "raylane/image/write_image.h"
#include "support/cli_run.h"
#include "support/jpeg_writer.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::read_file;
using testing::run_cli;
using testing::temp_dir;
using testing::write_file;

TEST(CliDiff, ReportsTheDifferenceAndExitsByTolerance) {
  std::string dir = temp_dir();
  Image a(4, 2), b(4, 2), small(2, 2);
  b.set(1, 1, glm::vec3(0.6f, 0, 0));  // one channel of 24 differs by 0.6: RMSE = sqrt(0.36 / 24)
  ASSERT_TRUE(write_image(dir + "/a.pfm", a).ok());
  ASSERT_TRUE(write_image(dir + "/b.pfm", b).ok());
  ASSERT_TRUE(write_image(dir + "/small.pfm", small).ok());

  auto same = run_cli("diff a.pfm a.pfm", dir);
  EXPECT_EQ(same.status, 0) << same.out;
  EXPECT_NE(same.out.find("rmse 0 "), std::string::npos) << same.out;

  auto differ = run_cli("diff b.pfm a.pfm", dir);
  EXPECT_EQ(differ.status, 1) << differ.out;
  EXPECT_NE(differ.out.find("rmse 0.122474 "), std::string::npos) << differ.out;
  EXPECT_NE(differ.out.find("max_abs 0.6"), std::string::npos) << differ.out;
  EXPECT_EQ(run_cli("diff b.pfm a.pfm --tol 0.2", dir).status, 0);

  EXPECT_EQ(run_cli("diff small.pfm a.pfm", dir).status, 2);
  EXPECT_EQ(run_cli("diff missing.pfm a.pfm", dir).status, 2);
  EXPECT_EQ(run_cli("diff a.pfm", dir).status, 2);
  EXPECT_EQ(run_cli("diff a.pfm a.pfm --tol -1", dir).status, 2);
  auto sizes = run_cli("diff small.pfm a.pfm", dir);
  EXPECT_NE(sizes.out.find("small.pfm is 2x2 and a.pfm is 4x2"), std::string::npos) << sizes.out;
}

// A NaN or infinite pixel is a difference no tolerance forgives, and the output says so.
TEST(CliDiff, NonFinitePixelsDifferBeyondAnyTolerance) {
  std::string dir = temp_dir();
  Image a(2, 2), nan(2, 2);
  nan.set(1, 0, glm::vec3(std::nanf(""), 0, 0));
  ASSERT_TRUE(write_image(dir + "/a.pfm", a).ok());
  ASSERT_TRUE(write_image(dir + "/nan.pfm", nan).ok());
  for (std::string args :
       {"diff nan.pfm a.pfm --tol 1e30", "diff a.pfm nan.pfm --tol 1e30", "diff nan.pfm nan.pfm"}) {
    auto r = run_cli(args, dir);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.out;
    EXPECT_NE(r.out.find("1 channel value is NaN or infinite"), std::string::npos) << r.out;
  }
}

// Where the largest difference is: the pixel (column, row from the top left) and channel.
TEST(CliDiff, ReportsThePixelOfTheLargestDifference) {
  std::string dir = temp_dir();
  Image a(4, 3), b(4, 3);
  b.set(3, 0, glm::vec3(0, 0.2f, 0));
  b.set(2, 1, glm::vec3(0, 0, -0.5f));  // value 3·(1·4 + 2) + 2 = 20 of the 36
  ASSERT_TRUE(write_image(dir + "/a.pfm", a).ok());
  ASSERT_TRUE(write_image(dir + "/b.pfm", b).ok());
  auto r = run_cli("diff b.pfm a.pfm", dir);
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("max_abs 0.5 max_x 2 max_y 1 max_channel 2\n"), std::string::npos) << r.out;
}

// --heatmap: sqrt(mean over a pixel's channels of (a − r)² / (r² + 0.01)), never over an input.
TEST(CliDiff, HeatmapIsThePerPixelRelativeError) {
  std::string dir = temp_dir();
  Image ref(3, 2), b(3, 2);
  ref.set(0, 0, glm::vec3(1, 1, 1));
  b.set(0, 0, glm::vec3(1, 1, 1));
  b.set(2, 1, glm::vec3(0.6f, 0, 0));  // sqrt(0.36 / 0.01 / 3) = sqrt(12)
  b.set(1, 0, glm::vec3(0, 0.2f, 0));  // sqrt(0.04 / 0.01 / 3) = sqrt(4 / 3)
  ASSERT_TRUE(write_image(dir + "/ref.pfm", ref).ok());
  ASSERT_TRUE(write_image(dir + "/b.pfm", b).ok());
  auto r = run_cli("diff b.pfm ref.pfm --heatmap h.pfm", dir);
  ASSERT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("h.pfm\n"), std::string::npos) << r.out;
  auto h = read_image(dir + "/h.pfm");
  ASSERT_TRUE(h.ok()) << h.error();
  ASSERT_EQ(h->width, 3u);
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 3; ++x) {
      float want = x == 2 && y == 1 ? std::sqrt(12.0f) : x == 1 && y == 0 ? std::sqrt(4.0f / 3) : 0;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(h->at(x, y)[c], want, 1e-5f) << x << " " << y;
    }
  std::string before = read_file(dir + "/ref.pfm");
  auto onto_input = run_cli("diff b.pfm ref.pfm --heatmap ref.pfm", dir);
  EXPECT_EQ(onto_input.status, 2) << onto_input.out;
  EXPECT_EQ(read_file(dir + "/ref.pfm"), before);
  EXPECT_EQ(run_cli("diff b.pfm ref.pfm --heatmap h.txt", dir).status, 2);
}

// An 8-bit image as a BMP or TGA file (24-bit, rows bottom first, BGR), by the formats' own
// layouts: the BMP's 54-byte header with rows padded to 4 bytes, the TGA's 18-byte header.
std::string bmp_bytes(const std::vector<std::array<uint8_t, 3>>& rgb, int w, int h) {
  int row = (3 * w + 3) / 4 * 4;
  auto le = [](std::string& s, uint32_t v, int n) {
    for (int i = 0; i < n; ++i)
      s.push_back(char(v >> (8 * i) & 0xff));
  };
  std::string s = "BM";
  le(s, 54 + row * h, 4), le(s, 0, 4), le(s, 54, 4);
  le(s, 40, 4), le(s, w, 4), le(s, h, 4), le(s, 1, 2), le(s, 24, 2), le(s, 0, 4);
  le(s, row * h, 4), le(s, 2835, 4), le(s, 2835, 4), le(s, 0, 4), le(s, 0, 4);
  for (int y = h - 1; y >= 0; --y) {
    for (int x = 0; x < w; ++x)
      for (int c = 2; c >= 0; --c)
        s.push_back(char(rgb[y * w + x][c]));
    s.append(std::size_t(row - 3 * w), '\0');
  }
  return s;
}

std::string tga_bytes(const std::vector<std::array<uint8_t, 3>>& rgb, int w, int h) {
  std::string s = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, char(w), 0, char(h), 0, 24, 0};
  for (int y = h - 1; y >= 0; --y)
    for (int x = 0; x < w; ++x)
      for (int c = 2; c >= 0; --c)
        s.push_back(char(rgb[y * w + x][c]));
  return s;
}

// convert and diff read what textures may be: the same pixels as PNG, BMP and TGA are the same
// image (0 and 255 are linear 0 and 1 exactly in sRGB), and convert writes them as float.
TEST(CliDiff, ConvertAndDiffReadPngJpegTgaAndBmp) {
  std::string dir = temp_dir();
  Image img(2, 2);
  img.set(0, 0, glm::vec3(1, 0, 0)), img.set(1, 0, glm::vec3(0, 1, 0));
  img.set(0, 1, glm::vec3(0, 0, 1)), img.set(1, 1, glm::vec3(1, 1, 1));
  ASSERT_TRUE(write_image(dir + "/img.png", img).ok());
  std::vector<std::array<uint8_t, 3>> bytes = {
      {255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}};
  write_file(dir + "/img.bmp", bmp_bytes(bytes, 2, 2));
  write_file(dir + "/img.tga", tga_bytes(bytes, 2, 2));
  for (const char* args :
       {"diff img.bmp img.png", "diff img.tga img.png", "diff img.png img.bmp"}) {
    auto r = run_cli(args, dir);
    EXPECT_EQ(r.status, 0) << args << "\n" << r.out;
    EXPECT_NE(r.out.find("rmse 0 "), std::string::npos) << args << "\n" << r.out;
  }
  ASSERT_EQ(run_cli("convert img.tga img.pfm", dir).status, 0);
  auto pfm = read_image(dir + "/img.pfm");
  ASSERT_TRUE(pfm.ok()) << pfm.error();
  EXPECT_EQ(pfm->rgb, img.rgb);
  // A flat 8×8 JPEG comes back within a code or two of its samples (support/jpeg_writer.h):
  // within 0.02 of the BMP of the same samples, in linear terms.
  std::vector<std::array<uint8_t, 3>> flat(64, {200, 120, 40});
  std::vector<uint8_t> samples;
  for (const auto& p : flat)
    samples.insert(samples.end(), p.begin(), p.end());
  write_file(dir + "/flat.jpg", testing::jpeg_bytes(samples, 8, 8, 3));
  write_file(dir + "/flat.bmp", bmp_bytes(flat, 8, 8));
  auto jpeg = run_cli("diff flat.jpg flat.bmp --tol 0.02", dir);
  EXPECT_EQ(jpeg.status, 0) << jpeg.out;
}

}  // namespace
}  // namespace raylane
