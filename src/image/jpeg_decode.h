// JPEG through libjpeg-turbo (Debian's libjpeg62-turbo-dev), behind a small internal interface
// (src/image only). libjpeg-turbo is fuzzed continuously upstream (OSS-Fuzz); stb_image 2.27's
// JPEG reader is not safe on damaged files (docs/design.md, "Images in").
//
// Guards on top of the library's own checks (why each one, in jpeg_decode.cpp):
// - every libjpeg error, and every corrupt-data warning, is an error here (no grey-filled
//   half images); only "extraneous bytes before a marker" is tolerated, as every viewer does;
// - arithmetic-coded files are refused: a block can cost less than a bit there, so the
//   pixels-per-byte bound that input_image.cpp checks before decoding would not hold;
// - at most kMaxJpegScans scans: a progressive file of many tiny scans re-walks the whole
//   image per scan, a hang in all but name;
// - libjpeg's own memory (a progressive file keeps every coefficient) runs under a budget.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace raylane::jpeg {

inline constexpr int kMaxJpegScans = 64;

struct Header {
  uint32_t width = 0, height = 0;
  int components = 0;  // 1 grey, 3 YCbCr or RGB, 4 CMYK/YCCK (inks, made RGB)
};

// The frame header (SOF): size and components; false with the reason otherwise.
bool probe(std::string_view bytes, Header& out, std::string& why);

// The pixels as 8-bit sRGB-encoded RGB, top row first, `h.width·h.height·3` bytes. libjpeg may
// allocate at most `budget_bytes` of its own memory.
bool decode(std::string_view bytes, const Header& h, uint64_t budget_bytes,
            std::vector<uint8_t>& rgb, std::string& why);

}  // namespace raylane::jpeg
