// Hostile images (docs/design.md, "Images in"): a decompression bomb is refused from its header
// before it is decoded, a file is read whole only after its first bytes are an image's, `info`
// reads headers only, and an OpenEXR luminance-chroma file reads as its colour, never as zeros.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <string>

#include "raylane/core/alloc_budget.h"
#include "raylane/core/strings.h"
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
  // At the default image memory, however large, the ratio rule refuses it.
  auto img = decode_input_image(bomb, "bomb.png", uint64_t(64) << 30);
  ASSERT_FALSE(img);
  EXPECT_NE(img.error().find("decoding its 8192x8192 pixels takes 1.2 GiB from a file of " +
                             std::to_string(bomb.size()) + " bytes, more than 1024 times its size"),
            std::string::npos)
      << img.error();
  EXPECT_NE(img.error().find("--image-memory 1217 reads it"), std::string::npos) << img.error();
  // An image memory the user chose lifts the rule; the memory left still decides.
  auto chosen = decode_input_image(bomb, "bomb.png", kDefaultImageMemory, true);
  ASSERT_FALSE(chosen);
  EXPECT_NE(chosen.error().find("decoding its 8192x8192 pixels takes 1.2 GiB; the image memory "
                                "left is 192.0 MiB (--image-memory MIB raises it)"),
            std::string::npos)
      << chosen.error();
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
  auto longer = read_input_image(dir + "/long.png", kDefaultImageMemory);
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

uint32_t little_endian_u32(const std::string& b, std::size_t at) {
  uint32_t v = 0;
  for (int k = 3; k >= 0; --k)
    v = v << 8 | uint8_t(b[at + std::size_t(k)]);
  return v;
}

std::string le32(uint32_t v) {
  return {char(v), char(v >> 8), char(v >> 16), char(v >> 24)};
}

// Bytes from hex digits (the fuzzer's file below).
std::string from_hex(std::string_view hex) {
  std::string out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2)
    out += char(std::stoi(std::string(hex.substr(i, 2)), nullptr, 16));
  return out;
}

// A luminance-chroma file found by the image fuzzer: its "compression" attribute declares 33
// bytes, which OpenEXRCore accepts; OpenEXR 3.1's C++ reader, which decodes such files, reads
// the one byte a compression has and goes on from there, to a "software" string declaring
// 1,912,602,637 bytes, and resized a string to that (1.9 GB) before reading it. The header is
// now walked first as that reader walks it: the file is refused by the compression's size;
// with that size mended, by the string's size against the bytes left; and a string one byte
// past the end, or of a size read as a negative int32, likewise.
TEST(ExrLuminanceChroma, AnAttributeLargerThanTheFileIsRefusedBeforeItIsRead) {
  const std::string bytes = from_hex(
      "762f3101020000006368616e6e656c730063686c697374003900000042590001000000010000000200000002"
      "0000005259000100000001000000020000000200000059000100000000000000010000000100000000636f6d"
      "7072657373696f6e00636f6d7072657373696f6e0021000000036461746157696e646f7700626f7832690010"
      "00000000000000000000000700000005000000646973706c617957696e646f7700626f783269001000000000"
      "000000000000000700000005000000656e746572007632660008000000000000000000000073637265656e57"
      "696e646f77576964746800666c6f617400040000000000803f736f66747761726500737472696e67000d0000"
      "72007632660008000000000000000000000073637265656e57696e646f77576964746800666c6f6174000400"
      "00000000803f0043010000000000000000000082000000785e5bfdef6dc5469e65aadf8ae4eedc39a2af17a0"
      "a7a7af77e3faf52f33f3b9044ea9c4705cbf7ee31a909f79fdfaced56bd6ac5e7974f7ee3906ebb7c7ad5e03"
      "e2ae29590362ac5eb3b9aaa6e60f676363724b73636353436343436323906cfcdcd1dcd456fd7a6a1d48048c"
      "c0b8e13f906caeabade28070a1a20d8d001fd24fbc");
  ASSERT_EQ(bytes.size(), 461u);
  auto img = decode_exr(bytes);
  ASSERT_FALSE(img);
  EXPECT_NE(img.error().find("attribute \"compression\" of type compression declares 33 bytes"),
            std::string::npos)
      << img.error();
  // The compression's size mended to its one byte: the C++ reader's view (it read one byte and
  // went on), where the string's size is what is wrong.
  const std::size_t compression_at = bytes.find(std::string("compression\0compression\0", 24)) + 24;
  std::string mended = bytes;
  mended[compression_at] = 1;
  const std::size_t size_at = mended.find(std::string("software\0string\0", 16)) + 16;
  ASSERT_EQ(little_endian_u32(mended, size_at), 1912602637u);
  for (uint32_t size : {1912602637u, uint32_t(mended.size() - size_at - 4 + 1), 0xffffffffu}) {
    std::string patched = mended;
    for (int k = 0; k < 4; ++k)
      patched[size_at + std::size_t(k)] = char((size >> (8 * k)) & 0xffu);
    auto refused = decode_exr(patched);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().find(cat("declares ", size, " bytes")), std::string::npos)
        << refused.error();
  }
}

// The position just past an EXR header's attributes (its empty name), where the offset table
// starts: a little-endian 32-bit size follows each attribute's name and type.
std::size_t exr_header_end(const std::string& b) {
  std::size_t pos = 8;
  for (;;) {
    const std::size_t name_end = b.find('\0', pos);
    if (name_end == pos) return pos + 1;
    const std::size_t type_end = b.find('\0', name_end + 1);
    pos = type_end + 1 + 4 + little_endian_u32(b, type_end + 1);
  }
}

// A damaged luminance-chroma file of 8x6 pixels with a second "dataWindow" attribute 2^24
// pixels wide after the first (its offset table moved on by the bytes inserted): OpenEXRCore
// reads it as 8x6, OpenEXR's C++ reader keeps the later window, and its RgbaInputFile
// constructor allocated buffers by that width (4 GiB) before the size could be compared. The
// C++ reader's header is now read and compared first: the file is refused, and no more is
// allocated than the file needs (the sanitizer builds' allocator limits would catch 4 GiB).
TEST(ExrLuminanceChroma, AHeaderReadAtAnotherSizeByTheCppReaderIsRefusedBeforeItAllocates) {
  auto grey = [](int, int) { return glm::vec3(0.5f); };
  std::string bytes = testing::exr_luminance_chroma(8, 6, grey);
  ASSERT_TRUE(decode_exr(bytes));
  std::string window = std::string("dataWindow\0box2i\0", 17) + le32(16);
  for (uint32_t v : {0u, 0u, (1u << 24) - 1, 5u})
    window += le32(v);
  const std::size_t at = bytes.find(std::string("dataWindow\0box2i\0", 17)) + 17 + 4 + 16;
  const std::size_t table = exr_header_end(bytes);
  bytes.insert(at, window);
  // One chunk (ZIP holds 16 scan lines): its 64-bit offset moves by the inserted bytes.
  const std::size_t chunk = little_endian_u32(bytes, table + window.size()) + window.size();
  for (int k = 0; k < 4; ++k)
    bytes[table + window.size() + std::size_t(k)] = char((chunk >> (8 * k)) & 0xffu);
  auto info = probe_exr(bytes);
  ASSERT_TRUE(info) << info.error();
  ASSERT_EQ(info->width, 8u);  // the core's reading
  // A budget of 1 GiB: without the check, the 4 GiB allocation fails inside OpenEXR instead.
  AllocBudget budget(uint64_t(1) << 30);
  auto img = decode_exr(bytes);
  EXPECT_LT(budget.peak(), uint64_t(16) << 20);
  ASSERT_FALSE(img);
  EXPECT_NE(img.error().find("reads as 8x6 and as 16777216x6"), std::string::npos) << img.error();
}

}  // namespace
}  // namespace raylane
