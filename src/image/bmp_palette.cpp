// Palette BMPs checked before stb_image decodes them. stb (2.27, stbi__bmp_load) reads a
// palette of psize entries into a stack array pal[256][4] and then looks every pixel's index up
// in it without comparing the index with psize: an index past a short palette returns whatever
// the stack held, so two decodes of one damaged file differ (found by fuzz_image). This file
// walks the header, the palette and the indices the way stb does and refuses such files.
#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>

#include "image/stb_decode.h"
#include "raylane/core/strings.h"

namespace raylane::stb {

namespace {

// A byte of the file as stb's memory reader gives it: 0 past the end. stb reads a truncated
// header on, as zeros, so the header is read here the same way (fuzz_image found a BMP cut off
// after its bit count that stb decoded from an uninitialised palette while this check had taken
// the short file for one stb refuses).
uint32_t byte_at(std::string_view b, std::size_t at) {
  return at < b.size() ? uint8_t(b[at]) : 0u;
}

uint32_t le16(std::string_view b, std::size_t at) {
  return byte_at(b, at) | byte_at(b, at + 1) << 8;
}

uint32_t le32(std::string_view b, std::size_t at) {
  return le16(b, at) | le16(b, at + 2) << 16;
}

// The bytes stb reads as pixel indices, from `at` on: its memory reader answers 0 past the end.
struct ByteReader {
  std::string_view b;
  std::size_t at;
  uint32_t next() { return at < b.size() ? uint8_t(b[at++]) : 0u; }
  void skip(std::size_t n) { at = n > b.size() - std::min(at, b.size()) ? b.size() : at + n; }
};

// The highest palette index of the pixel rows, read as stbi__bmp_load reads them (1-bit rows
// bit by bit from the top bit, 4-bit rows high nibble first, rows padded to 4 bytes).
uint32_t highest_index(ByteReader r, uint32_t width, uint32_t height, uint32_t bits) {
  const uint32_t row_bytes = bits == 1 ? (width + 7) / 8 : bits == 4 ? (width + 1) / 2 : width;
  const uint32_t pad = (4 - row_bytes % 4) % 4;
  const uint32_t per_byte = 8 / bits, mask = (1u << bits) - 1;
  uint32_t highest = 0;
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; x += per_byte) {
      uint32_t v = r.next();
      for (uint32_t k = 0; k < per_byte && x + k < width; ++k)
        highest = std::max(highest, (v >> (8 - bits * (k + 1))) & mask);
    }
    r.skip(pad);
  }
  return highest;
}

}  // namespace

bool check_bmp_palette(std::string_view b, std::string& why) {
  // Not a BMP stb would decode from a palette: its own checks answer for it.
  if (byte_at(b, 0) != 'B' || byte_at(b, 1) != 'M') return true;
  const uint32_t hsz = le32(b, 14);
  if (hsz != 12 && hsz != 40 && hsz != 56 && hsz != 108 && hsz != 124) return true;
  const bool core = hsz == 12;
  const uint32_t bits = le16(b, core ? 24 : 28);
  if (bits != 1 && bits != 4 && bits != 8) return true;
  const uint32_t width = core ? le16(b, 18) : le32(b, 18);
  const int32_t signed_height = int32_t(core ? le16(b, 20) : le32(b, 22));
  // stb refuses sizes past 2^24 itself, and the pixel limit is checked before decoding.
  const uint32_t height =
      signed_height < 0 ? uint32_t(0) - uint32_t(signed_height) : uint32_t(signed_height);
  if (width > (1u << 24) || height > (1u << 24)) return true;
  // stb's palette size: the bytes between the header and the pixels' offset, 3 or 4 per entry
  // (its core-header formula subtracts 24, not 26: copied as it is, so both count alike). It
  // divides by 3 (rounding toward 0) but shifts right by 2 (rounding down), so an offset inside
  // the header gives it a negative size, and that it does not refuse: it reads no palette at
  // all and looks every pixel up in its uninitialised one (found by fuzz_image). Such a file
  // has no palette to read, and is refused here.
  const int64_t offset = int32_t(le32(b, 10));
  const int64_t psize = core ? (offset - 14 - 24) / 3 : (offset - 14 - int64_t(hsz)) >> 2;
  if (psize == 0 || psize > 256) return true;  // stb refuses these ("Corrupt BMP")
  if (psize < 0) {
    why = cat("expected a palette between the header and the pixels, found the pixels' offset ",
              offset, " inside the ", hsz, "-byte header");
    return false;
  }
  // Where stb starts reading pixels: the offset, or the file's end if the offset lies inside
  // the palette (stb's skip by a negative count jumps to the end).
  const int64_t after_palette = 14 + int64_t(hsz) + psize * (core ? 3 : 4);
  std::size_t start = offset < after_palette ? b.size() : std::size_t(offset);
  uint32_t highest = highest_index(ByteReader{b, start}, width, height, bits);
  if (highest < psize) return true;
  why = cat("expected palette indices below the palette's ", psize, " entries, found index ",
            highest);
  return false;
}

}  // namespace raylane::stb
