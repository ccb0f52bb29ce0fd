// stb_image behind a small internal interface (src/image only): its header is compiled into one
// translation unit, with its allocations counted against a budget per call.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace raylane::stb {

struct Header {
  int width = 0, height = 0, channels = 0;
  bool is_16bit = false, is_hdr = false;
};

// The header of a PNG, JPEG, BMP, TGA or HDR file; false with stb's reason otherwise.
bool probe(std::string_view bytes, Header& out, std::string& why);

// Decodes to 3 channels: 8-bit samples in `u8`, 16-bit in `u16` or floats in `f32`, by the
// header's kind. stb_image may allocate at most `budget_bytes` in all during the call;
// false with stb's reason (or "out of memory" past the budget).
struct Pixels {
  std::vector<uint8_t> u8;
  std::vector<uint16_t> u16;
  std::vector<float> f32;
};
bool decode(std::string_view bytes, const Header& h, uint64_t budget_bytes, Pixels& out,
            std::string& why);

// False, with the reason, for a BMP of 1, 4 or 8 bits a pixel that stb would decode although a
// pixel's index lies past its palette (stb would read that entry from uninitialised memory);
// true for every other file. decode() calls it (src/image/bmp_palette.cpp).
bool check_bmp_palette(std::string_view bytes, std::string& why);

}  // namespace raylane::stb
