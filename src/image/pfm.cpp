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

Result<PfmHeader> parse_pfm_header(std::string_view b) {
  std::size_t pos = 0;
  if (token(b, pos) != "PF") return Error{"not a colour PFM file (no PF magic)"};
  PfmHeader h;
  auto num = [&](auto& v) {
    std::string_view t = token(b, pos);
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    return ec == std::errc() && p == t.data() + t.size();
  };
  if (!num(h.width) || !num(h.height) || h.width == 0 || h.height == 0)
    return Error{"bad PFM size"};
  if (!num(h.scale) || h.scale == 0) return Error{"bad PFM scale"};
  if (uint64_t(h.width) * h.height > kMaxImagePixels)
    return Error{
        cat("image has ", uint64_t(h.width) * h.height, " pixels; the limit is 2^28 (268435456)")};
  h.data_offset = pos + 1;  // the single whitespace character after the scale
  uint64_t need = uint64_t(h.width) * h.height * 12;
  if (h.data_offset > b.size() || b.size() - h.data_offset < need)
    return Error{"truncated PFM data"};
  return h;
}

Result<Image> decode_pfm(std::string_view b) {
  auto h = parse_pfm_header(b);
  if (!h) return Error{h.error()};
  const uint32_t w = h->width, ht = h->height;
  std::size_t pos = h->data_offset;
  Image img(w, ht);
  bool swap = h->scale > 0;  // positive scale: big endian
  for (uint32_t row = 0; row < ht; ++row) {
    uint32_t y = ht - 1 - row;
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
