// JPEG in (image/input_image.h through libjpeg-turbo): colours and rows where they belong, every
// coding raylane reads, and the files it refuses — each with its reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "raylane/image/input_image.h"
#include "support/jpeg_writer.h"

namespace raylane {
namespace {

using testing::jpeg_bytes;
using testing::JpegKind;

// Four flat 8×8 blocks (one per quadrant of a 16×16 image) in sRGB codes: top-left, top-right,
// bottom-left, bottom-right.
constexpr std::array<std::array<uint8_t, 3>, 4> kQuadrants = {
    {{200, 30, 40}, {20, 180, 60}, {10, 40, 220}, {250, 250, 120}}};

int quadrant(uint32_t x, uint32_t y) {
  return (y >= 8 ? 2 : 0) + (x >= 8 ? 1 : 0);
}

std::vector<uint8_t> quadrant_samples() {
  std::vector<uint8_t> s;
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x)
      for (uint8_t c : kQuadrants[quadrant(x, y)])
        s.push_back(c);
  return s;
}

// A flat block at quality 100 keeps its DC coefficient exactly (quantiser 1); what moves a code
// is the RGB → YCbCr → RGB round trip, which rounds each of Y, Cb, Cr to an integer (≤ 0.5
// each) and each RGB result again: |ΔR| ≤ 0.5 + 1.402·0.5 + 0.5 < 2 codes, likewise G and B.
constexpr int kCodeSlack = 2;

void expect_code(float linear, int code, const char* what) {
  float lo = float(srgb_to_linear(std::max(code - kCodeSlack, 0) / 255.0));
  float hi = float(srgb_to_linear(std::min(code + kCodeSlack, 255) / 255.0));
  EXPECT_GE(linear, lo) << what << " code " << code;
  EXPECT_LE(linear, hi) << what << " code " << code;
}

TEST(Jpeg, ColourIsSrgbDecodedWithTheTopRowFirst) {
  auto img = decode_input_image(jpeg_bytes(quadrant_samples(), 16, 16, 3), "q.jpg");
  ASSERT_TRUE(img) << img.error();
  ASSERT_EQ(img->width, 16u);
  ASSERT_EQ(img->height, 16u);
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      const auto& want = kQuadrants[quadrant(x, y)];
      glm::vec3 got = img->at(x, y);
      expect_code(got.x, want[0], "R");
      expect_code(got.y, want[1], "G");
      expect_code(got.z, want[2], "B");
    }
}

TEST(Jpeg, ProgressiveGivesTheBaselinePixels) {
  // The same quantised coefficients sent in another order: the same image, exactly.
  auto base = decode_input_image(jpeg_bytes(quadrant_samples(), 16, 16, 3), "b.jpg");
  auto prog = decode_input_image(jpeg_bytes(quadrant_samples(), 16, 16, 3, JpegKind::kProgressive),
                                 "p.jpg");
  ASSERT_TRUE(base) << base.error();
  ASSERT_TRUE(prog) << prog.error();
  EXPECT_EQ(prog->rgb, base->rgb);
}

TEST(Jpeg, GreyBecomesRgbWithEqualChannels) {
  std::vector<uint8_t> grey(8 * 16);
  for (std::size_t i = 0; i < grey.size(); ++i)
    grey[i] = i < 64 ? 40 : 210;  // top block dark, bottom block light
  auto img = decode_input_image(jpeg_bytes(grey, 8, 16, 1), "g.jpg");
  ASSERT_TRUE(img) << img.error();
  for (uint32_t y = 0; y < 16; ++y) {
    glm::vec3 c = img->at(3, y);
    EXPECT_EQ(c.x, c.y);
    EXPECT_EQ(c.y, c.z);
    // Grey is coded as Y alone: only the 8×8 DCT's rounding moves it, by at most one code.
    float lo = float(srgb_to_linear((y < 8 ? 39 : 209) / 255.0));
    float hi = float(srgb_to_linear((y < 8 ? 41 : 211) / 255.0));
    EXPECT_GE(c.x, lo) << y;
    EXPECT_LE(c.x, hi) << y;
  }
}

TEST(Jpeg, ATruncatedFileIsAnErrorNotAGreyFilledImage) {
  std::string bytes = jpeg_bytes(quadrant_samples(), 16, 16, 3);
  std::size_t scan = bytes.find("\xff\xda");  // SOS: the entropy-coded data follows
  ASSERT_NE(scan, std::string::npos);
  bytes.resize(scan + (bytes.size() - scan) / 2);  // the header survives, the scan is cut
  ASSERT_TRUE(probe_input_image(bytes, "t.jpg"));
  auto img = decode_input_image(bytes, "t.jpg");
  ASSERT_FALSE(img);
  EXPECT_NE(img.error().find("cannot decode the JPEG data"), std::string::npos) << img.error();
}

TEST(Jpeg, ArithmeticCodingIsRefusedByName) {
  auto arith =
      probe_input_image(jpeg_bytes(quadrant_samples(), 16, 16, 3, JpegKind::kArithmetic), "a.jpg");
  ASSERT_FALSE(arith);
  EXPECT_NE(arith.error().find("arithmetic-coded"), std::string::npos) << arith.error();
}

// libjpeg writes CMYK with Adobe's marker, whose inks are stored inverted (255: no ink): each
// channel is C·K/255 of the stored bytes. Flat 8×8 blocks at quality 100 (every quantiser 1)
// come back within 1 code of what was stored (the DCT's integer rounding).
TEST(Jpeg, AdobeCmykIsReadAsItsColour) {
  const std::array<std::array<uint8_t, 4>, 4> inks = {
      {{255, 255, 255, 255}, {200, 100, 50, 255}, {255, 255, 255, 128}, {40, 220, 90, 200}}};
  std::vector<uint8_t> cmyk;
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x)
      for (uint8_t c : inks[quadrant(x, y)])
        cmyk.push_back(c);
  auto img = decode_input_image(jpeg_bytes(cmyk, 16, 16, 4), "c.jpg");
  ASSERT_TRUE(img) << img.error();
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      const auto& ink = inks[quadrant(x, y)];
      for (int c = 0; c < 3; ++c) {
        double code = ink[c] * ink[3] / 255.0;
        double lo = srgb_to_linear(std::max(0.0, code - 1.5) / 255);
        double hi = srgb_to_linear(std::min(255.0, code + 1.5) / 255);
        float got = img->at(x, y)[c];
        EXPECT_TRUE(got >= lo && got <= hi) << x << "," << y << " channel " << c << ": " << got;
      }
    }
}

TEST(Jpeg, MoreScansThanTheLimitAreRefused) {
  // 1 DC scan + 63 AC scans for each of 3 components: 190, past the limit of 64.
  std::string bytes = jpeg_bytes(quadrant_samples(), 16, 16, 3, JpegKind::kManyScans);
  auto img = decode_input_image(bytes, "m.jpg");
  ASSERT_FALSE(img);
  EXPECT_NE(img.error().find("more than 64 scans"), std::string::npos) << img.error();
}

// The SOF0 marker's height and width fields (ITU T.81 B.2.2: FF C0, length, precision, Y, X).
std::string with_size(std::string bytes, uint16_t w, uint16_t h) {
  std::size_t sof = bytes.find("\xff\xc0");
  EXPECT_NE(sof, std::string::npos);
  bytes[sof + 5] = char(h >> 8), bytes[sof + 6] = char(h);
  bytes[sof + 7] = char(w >> 8), bytes[sof + 8] = char(w);
  return bytes;
}

TEST(Jpeg, AnnouncedSizeBeyondWhatTheFileHoldsIsRefusedBeforeDecoding) {
  std::string bytes = jpeg_bytes(quadrant_samples(), 16, 16, 3);
  auto fits = probe_input_image(with_size(bytes, 64, 64), "f.jpg");
  ASSERT_TRUE(fits) << fits.error();
  EXPECT_EQ(fits->width, 64u);
  auto big = probe_input_image(with_size(bytes, 8000, 8000), "big.jpg");
  ASSERT_FALSE(big);
  EXPECT_NE(big.error().find("more than"), std::string::npos) << big.error();
}

}  // namespace
}  // namespace raylane
