#include "raylane/image/rgbe.h"

#include <charconv>
#include <cmath>

#include "raylane/core/strings.h"

namespace raylane {

namespace {

// 255·2^119: the largest value whose exponent byte still fits.
constexpr float kMaxRgbe = 255.0f * 0x1p119f;
constexpr uint32_t kMinRleWidth = 8, kMaxRleWidth = 32767;

float clean(float v) {
  return v > 0 ? std::min(v, kMaxRgbe) : 0.0f;
}  // NaN → 0

// Appends one channel of a scanline in the RLE form: runs of ≥ 4 equal bytes as
// (128 + n, byte), everything else as literal dumps (n, bytes...), n ≤ 127 / 128.
void append_rle_channel(std::string& out, const uint8_t* data, uint32_t n) {
  uint32_t i = 0;
  while (i < n) {
    // Find the next run of at least 4.
    uint32_t run_start = i, run_len = 0;
    while (run_start < n) {
      run_len = 1;
      while (run_start + run_len < n && run_len < 127 &&
             data[run_start + run_len] == data[run_start])
        ++run_len;
      if (run_len >= 4) break;
      run_start += run_len;
    }
    if (run_start >= n) run_len = 0;
    // Literal dump up to the run.
    while (i < run_start) {
      uint32_t len = std::min<uint32_t>(128, run_start - i);
      out.push_back(char(len));
      out.append(reinterpret_cast<const char*>(data + i), len);
      i += len;
    }
    if (run_len >= 4) {
      out.push_back(char(128 + run_len));
      out.push_back(char(data[run_start]));
      i = run_start + run_len;
    }
  }
}

void append_scanline(std::string& out, const Image& image, uint32_t y) {
  uint32_t w = image.width;
  std::vector<uint8_t> channels(std::size_t(w) * 4);
  for (uint32_t x = 0; x < w; ++x) {
    glm::vec3 c = image.at(x, y);
    auto e = float_to_rgbe(c.x, c.y, c.z);
    for (int k = 0; k < 4; ++k)
      channels[std::size_t(k) * w + x] = e[k];
  }
  if (w < kMinRleWidth || w > kMaxRleWidth) {
    for (uint32_t x = 0; x < w; ++x)
      for (int k = 0; k < 4; ++k)
        out.push_back(char(channels[std::size_t(k) * w + x]));
    return;
  }
  out.push_back(2), out.push_back(2), out.push_back(char(w >> 8)), out.push_back(char(w & 255));
  for (int k = 0; k < 4; ++k)
    append_rle_channel(out, &channels[std::size_t(k) * w], w);
}

// A cursor over the file's bytes that never reads past the end.
struct Reader {
  std::string_view bytes;
  std::size_t pos = 0;

  std::size_t left() const { return bytes.size() - pos; }
  bool line(std::string_view& out) {
    if (pos >= bytes.size()) return false;
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string_view::npos) return false;
    out = bytes.substr(pos, end - pos);
    pos = end + 1;
    return true;
  }
};

bool parse_u32(std::string_view s, uint32_t& v) {
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && p == s.data() + s.size();
}

// "-Y H +X W": rows top to bottom, pixels left to right (the only orientation raylane reads).
Status parse_resolution(std::string_view line, uint32_t& w, uint32_t& h) {
  if (line.substr(0, 3) != "-Y ")
    return Error{cat("unsupported resolution line ", in_quotes(line))};
  std::size_t x = line.find(" +X ");
  if (x == std::string_view::npos || !parse_u32(line.substr(3, x - 3), h) ||
      !parse_u32(line.substr(x + 4), w) || w == 0 || h == 0)
    return Error{cat("bad resolution line ", in_quotes(line))};
  if (uint64_t(w) * h > kMaxImagePixels)
    return Error{cat("image has ", uint64_t(w) * h, " pixels; the limit is 2^28 (268435456)")};
  return ok_status();
}

Status read_header(Reader& r, RgbeFile& f, uint32_t& w, uint32_t& h) {
  std::string_view line;
  if (!r.line(line) || line.substr(0, 2) != "#?") return Error{"not a Radiance file (no #? line)"};
  while (true) {
    if (!r.line(line)) return Error{"truncated header"};
    if (line.empty()) break;
    if (line.substr(0, 7) == "FORMAT=") {
      if (line != "FORMAT=32-bit_rle_rgbe")
        return Error{cat("unsupported ", in_quotes(line), " (only 32-bit_rle_rgbe)")};
      continue;
    }
    if (line[0] != '#') f.metadata.emplace_back(line);
  }
  if (!r.line(line)) return Error{"missing resolution line"};
  return parse_resolution(line, w, h);
}

// Decodes one scanline (RLE or flat) into 4 channel arrays.
Status read_scanline(Reader& r, uint32_t w, std::vector<uint8_t>& ch) {
  if (r.left() < 4) return Error{"truncated scanline"};
  const auto* b = reinterpret_cast<const uint8_t*>(r.bytes.data() + r.pos);
  bool rle = w >= kMinRleWidth && w <= kMaxRleWidth && b[0] == 2 && b[1] == 2 && !(b[2] & 0x80);
  if (!rle) {
    if (r.left() < std::size_t(w) * 4) return Error{"truncated scanline"};
    for (uint32_t x = 0; x < w; ++x)
      for (int k = 0; k < 4; ++k)
        ch[std::size_t(k) * w + x] = b[x * 4 + k];
    r.pos += std::size_t(w) * 4;
    return ok_status();
  }
  if (((uint32_t(b[2]) << 8) | b[3]) != w) return Error{"scanline width does not match"};
  r.pos += 4;
  for (int k = 0; k < 4; ++k) {
    uint8_t* dst = &ch[std::size_t(k) * w];
    uint32_t x = 0;
    while (x < w) {
      if (r.left() < 1) return Error{"truncated scanline"};
      uint8_t count = uint8_t(r.bytes[r.pos++]);
      if (count > 128) {
        uint32_t n = count - 128u;
        if (x + n > w || r.left() < 1) return Error{"bad run length"};
        std::fill(dst + x, dst + x + n, uint8_t(r.bytes[r.pos++]));
        x += n;
      } else {
        if (count == 0 || x + count > w || r.left() < count) return Error{"bad literal length"};
        std::copy_n(reinterpret_cast<const uint8_t*>(r.bytes.data() + r.pos), count, dst + x);
        r.pos += count;
        x += count;
      }
    }
  }
  return ok_status();
}

}  // namespace

std::array<uint8_t, 4> float_to_rgbe(float r, float g, float b) {
  r = clean(r), g = clean(g), b = clean(b);
  float v = std::max(r, std::max(g, b));
  if (v < 1e-32f) return {0, 0, 0, 0};
  int e = 0;
  float scale = std::frexp(v, &e) * 256.0f / v;
  auto byte = [&](float c) { return uint8_t(std::min(255.0f, c * scale)); };
  return {byte(r), byte(g), byte(b), uint8_t(e + 128)};
}

glm::vec3 rgbe_to_float(const std::array<uint8_t, 4>& e) {
  if (e[3] == 0) return {0, 0, 0};
  float f = std::ldexp(1.0f, int(e[3]) - (128 + 8));
  return {e[0] * f, e[1] * f, e[2] * f};
}

std::string encode_rgbe(const Image& image, const std::vector<std::string>& metadata) {
  std::string out = "#?RADIANCE\nSOFTWARE=raylane\n";
  for (const auto& m : metadata)
    out.append(m).push_back('\n');
  out += cat("FORMAT=32-bit_rle_rgbe\n\n-Y ", image.height, " +X ", image.width, "\n");
  for (uint32_t y = 0; y < image.height; ++y)
    append_scanline(out, image, y);
  return out;
}

Result<RgbeSize> probe_rgbe(std::string_view bytes) {
  Reader r{bytes};
  RgbeFile f;
  RgbeSize size;
  if (Status s = read_header(r, f, size.width, size.height); !s) return Error{s.error()};
  return size;
}

namespace {

// The header and every scanline, each handed to on_row(y, ch) as its 4 channel planes
// (R, G, B, E, w bytes each) as it decodes.
template <class OnRow>
Status read_rgbe(std::string_view bytes, RgbeFile& f, uint32_t& w, uint32_t& h, OnRow on_row) {
  Reader r{bytes};
  if (Status s = read_header(r, f, w, h); !s) return s;
  // The fewest bytes a row can take: one header and runs of at most 127 per channel when it
  // is run-length encoded, 4 bytes a pixel when it is flat. A header that announces more rows
  // than the bytes left can hold is refused before the row buffer is sized from it.
  bool rle_possible = w >= kMinRleWidth && w <= kMaxRleWidth;
  uint64_t min_row = rle_possible ? 4 + 4 * 2 * ((uint64_t(w) + 126) / 127) : uint64_t(w) * 4;
  if (min_row * h > r.left())
    return Error{cat("the header announces ", w, "x", h, " pixels, at least ", min_row * h,
                     " bytes of data, and ", r.left(), " bytes follow it")};
  std::vector<uint8_t> ch(std::size_t(w) * 4);
  for (uint32_t y = 0; y < h; ++y) {
    if (Status s = read_scanline(r, w, ch); !s) return Error{cat(s.error(), " (row ", y, ")")};
    on_row(y, ch);
  }
  return ok_status();
}

}  // namespace

Result<RgbeFile> decode_rgbe(std::string_view bytes) {
  RgbeFile f;
  uint32_t w = 0, h = 0;
  // Rows are appended as they decode, so memory grows only with data actually present.
  Status s = read_rgbe(bytes, f, w, h, [&](uint32_t y, const std::vector<uint8_t>& ch) {
    f.image.width = w;
    for (uint32_t x = 0; x < w; ++x) {
      glm::vec3 c =
          rgbe_to_float({ch[x], ch[w + x], ch[2 * std::size_t(w) + x], ch[3 * std::size_t(w) + x]});
      f.image.rgb.insert(f.image.rgb.end(), {c.x, c.y, c.z});
    }
    f.image.height = y + 1;
  });
  if (!s) return Error{s.error()};
  return f;
}

Result<TexelImage> decode_rgbe_texels(std::string_view bytes) {
  RgbeFile f;
  TexelImage t;
  t.format = TexelFormat::kRgbe;
  uint32_t w = 0, h = 0;
  Status s = read_rgbe(bytes, f, w, h, [&](uint32_t y, const std::vector<uint8_t>& ch) {
    t.width = w;
    // The header's size was checked against the data that follows it before the first row.
    if (y == 0) t.packed.reserve(std::size_t(w) * h);
    for (uint32_t x = 0; x < w; ++x) {
      std::size_t k = x;
      t.packed.push_back(uint32_t(ch[k]) | uint32_t(ch[w + k]) << 8 |
                         uint32_t(ch[2 * std::size_t(w) + k]) << 16 |
                         uint32_t(ch[3 * std::size_t(w) + k]) << 24);
    }
    t.height = y + 1;
  });
  if (!s) return Error{s.error()};
  return t;
}

}  // namespace raylane
