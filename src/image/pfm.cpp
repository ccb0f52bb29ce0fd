#include "raylane/image/pfm.h"

#include <bit>
#include <charconv>
#include <cmath>
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
  std::string_view magic = token(b, pos);
  if (magic != "PF" && magic != "Pf") return Error{"not a PFM file (no PF or Pf magic)"};
  PfmHeader h;
  h.channels = magic == "PF" ? 3 : 1;
  auto num = [&](auto& v) {
    std::string_view t = token(b, pos);
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    return ec == std::errc() && p == t.data() + t.size();
  };
  if (!num(h.width) || !num(h.height) || h.width == 0 || h.height == 0)
    return Error{"bad PFM size"};
  // from_chars reads "nan" and "inf" too: a scale must be a finite number other than 0.
  if (!num(h.scale) || h.scale == 0 || !std::isfinite(h.scale))
    return Error{"bad PFM scale (expected a finite number other than 0)"};
  if (uint64_t(h.width) * h.height > kMaxImagePixels)
    return Error{
        cat("image has ", uint64_t(h.width) * h.height, " pixels; the limit is 2^28 (268435456)")};
  h.data_offset = pos + 1;  // the single whitespace character after the scale
  uint64_t need = uint64_t(h.width) * h.height * 4 * uint64_t(h.channels);
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
    for (std::size_t k = 0; k < std::size_t(w) * std::size_t(h->channels); ++k) {
      uint32_t bits;
      std::memcpy(&bits, b.data() + pos, 4);
      pos += 4;
      float v = std::bit_cast<float>(swap ? byteswap32(bits) : bits);
      if (h->channels == 3) {
        img.rgb[img.index(0, y) + k] = v;
      } else {  // grey: the value in all three channels
        std::size_t at = img.index(uint32_t(k), y);
        img.rgb[at] = img.rgb[at + 1] = img.rgb[at + 2] = v;
      }
    }
  }
  return img;
}

}  // namespace raylane
