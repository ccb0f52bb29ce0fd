#include "raylane/image/pfm.h"

#include <bit>
#include <charconv>
#include <cstring>

#include "raylane/core/strings.h"

namespace raylane {

namespace {

// The next whitespace-separated header token; advances `pos` past it.
std::string_view token(std::string_view b, std::size_t& pos) {
  while (pos < b.size() && (b[pos] == ' ' || b[pos] == '\n' || b[pos] == '\r' || b[pos] == '\t'))
    ++pos;
  std::size_t start = pos;
  while (pos < b.size() && !(b[pos] == ' ' || b[pos] == '\n' || b[pos] == '\r' || b[pos] == '\t'))
    ++pos;
  return b.substr(start, pos - start);
}

uint32_t byteswap32(uint32_t v) {
  return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

}  // namespace

std::string encode_pfm(const Image& image) {
  static_assert(std::endian::native == std::endian::little, "PFM writer assumes little endian");
  std::string out = cat("PF\n", image.width, " ", image.height, "\n-1.0\n");
  std::size_t row_bytes = std::size_t(image.width) * 3 * sizeof(float);
  for (uint32_t y = image.height; y-- > 0;)  // bottom row first
    out.append(reinterpret_cast<const char*>(&image.rgb[image.index(0, y)]), row_bytes);
  return out;
}

Result<Image> decode_pfm(std::string_view b) {
  std::size_t pos = 0;
  if (token(b, pos) != "PF") return Error{"not a colour PFM file (no PF magic)"};
  uint32_t w = 0, h = 0;
  double scale = 0;
  auto num = [&](auto& v) {
    std::string_view t = token(b, pos);
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    return ec == std::errc() && p == t.data() + t.size();
  };
  if (!num(w) || !num(h) || w == 0 || h == 0) return Error{"bad PFM size"};
  if (!num(scale) || scale == 0) return Error{"bad PFM scale"};
  if (uint64_t(w) * h > kMaxImagePixels)
    return Error{cat("image has ", uint64_t(w) * h, " pixels; the limit is 2^28 (268435456)")};
  ++pos;  // the single whitespace character after the scale
  uint64_t need = uint64_t(w) * h * 12;
  if (pos > b.size() || b.size() - pos < need) return Error{"truncated PFM data"};
  Image img(w, h);
  bool swap = scale > 0;  // positive scale: big endian
  for (uint32_t row = 0; row < h; ++row) {
    uint32_t y = h - 1 - row;
    for (std::size_t k = 0; k < std::size_t(w) * 3; ++k) {
      uint32_t bits;
      std::memcpy(&bits, b.data() + pos, 4);
      pos += 4;
      img.rgb[img.index(0, y) + k] = std::bit_cast<float>(swap ? byteswap32(bits) : bits);
    }
  }
  return img;
}

}  // namespace raylane
