#include "support/hostile_files.h"

#include <Imath/half.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfRgbaFile.h>

#include <cstdint>
#include <cstring>
#include <vector>

namespace raylane::testing {

namespace {

std::string be32(uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

// CRC-32 of PNG chunks (ISO 3309, as the PNG specification's annex D computes it).
uint32_t crc32(const std::string& bytes) {
  uint32_t c = 0xffffffffu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k)
      c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
  }
  return c ^ 0xffffffffu;
}

std::string png_chunk(const std::string& type, const std::string& data) {
  return be32(uint32_t(data.size())) + type + data + be32(crc32(type + data));
}

// Deflate's bits: fields least significant bit first, Huffman codes most significant first.
class BitWriter {
 public:
  void bits(uint32_t value, int n) {
    for (int k = 0; k < n; ++k)
      bit((value >> k) & 1);
  }
  void code(uint32_t value, int n) {
    for (int k = n - 1; k >= 0; --k)
      bit((value >> k) & 1);
  }
  std::string done() { return bytes_; }

 private:
  void bit(uint32_t b) {
    if (used_ == 0) bytes_.push_back('\0');
    bytes_.back() = char(bytes_.back() | (b << used_));
    used_ = (used_ + 1) % 8;
  }
  std::string bytes_;
  int used_ = 0;
};

// A zlib stream (RFC 1950) of n zero bytes in one fixed-Huffman block: a literal 0, then
// matches of length 258 at distance 1 (length code 285: 8 bits 11000101, distance code 0:
// 5 bits), then literal zeros for the rest (8 bits 00110000 each), then end of block (7 zero
// bits). Adler-32 of n zeros: s1 = 1, s2 = n mod 65521.
std::string zlib_zeros(uint64_t n) {
  BitWriter w;
  w.bits(1, 1);  // BFINAL
  w.bits(1, 2);  // BTYPE 01: fixed Huffman codes
  w.code(0x30, 8);
  uint64_t left = n - 1;
  for (; left >= 258; left -= 258) {
    w.code(0xc5, 8);
    w.code(0, 5);
  }
  for (; left > 0; --left)
    w.code(0x30, 8);
  w.code(0, 7);
  return std::string("\x78\x01", 2) + w.done() + be32(uint32_t(n % 65521) << 16 | 1);
}

// Writes into a string: RgbaOutputFile takes any OStream.
class StringStream : public Imf::OStream {
 public:
  StringStream() : Imf::OStream("memory.exr") {}
  void write(const char c[], int n) override {
    if (bytes.size() < pos_ + n) bytes.resize(pos_ + n);
    std::memcpy(bytes.data() + pos_, c, std::size_t(n));
    pos_ += uint64_t(n);
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = pos; }
  std::string bytes;

 private:
  uint64_t pos_ = 0;
};

}  // namespace

std::string png_zero_bomb(uint32_t w, uint32_t h) {
  std::string ihdr = be32(w) + be32(h) + std::string{1, 0, 0, 0, 0};  // 1-bit grey
  uint64_t raw = uint64_t(h) * (1 + (w + 7) / 8);  // each row: filter byte 0, then the bits
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) +
         png_chunk("IDAT", zlib_zeros(raw)) + png_chunk("IEND", "");
}

std::string ply_with_long_header(std::size_t comment_bytes) {
  std::string s = "ply\nformat binary_little_endian 1.0\n";
  const std::string line = "comment a long block of notes, as scanners and exporters write them\n";
  for (std::size_t n = 0; n < comment_bytes; n += line.size())
    s += line;
  s += "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  s.append(reinterpret_cast<const char*>(v), sizeof v);
  s.push_back(char(3));
  const int idx[3] = {0, 1, 2};
  s.append(reinterpret_cast<const char*>(idx), sizeof idx);
  return s;
}

std::string exr_luminance_chroma(int w, int h, const std::function<glm::vec3(int, int)>& colour,
                                 int x0, int y0) {
  std::vector<Imf::Rgba> pixels(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec3 c = colour(x, y);
      pixels[std::size_t(y) * w + x] = Imf::Rgba(c.x, c.y, c.z, 1.0f);
    }
  StringStream out;
  {
    const Imath::Box2i window({x0, y0}, {x0 + w - 1, y0 + h - 1});
    Imf::Header header(window, window);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::RgbaOutputFile file(out, header, Imf::WRITE_YC);
    file.setYCRounding(10, 10);  // keep half's 10 fraction bits (the default rounds Y to 7)
    // OpenEXR's frame buffer is addressed by absolute coordinates; the shift as an integer (see
    // src/image/exr_rgba.cpp).
    const std::ptrdiff_t shift = std::ptrdiff_t(x0) + std::ptrdiff_t(y0) * w;
    file.setFrameBuffer(
        reinterpret_cast<Imf::Rgba*>(reinterpret_cast<std::uintptr_t>(pixels.data()) -
                                     std::uintptr_t(shift) * sizeof(Imf::Rgba)),
        1, std::size_t(w));
    file.writePixels(h);
  }
  return out.bytes;
}

std::string flat_hdr(uint32_t w, uint32_t h) {
  std::string row = {2, 2, char(w >> 8), char(w & 0xff)};
  // Mantissas 128 and exponent 129: 128 · 2^(129 − 136) = 1 in each channel.
  for (char value : {char(128), char(128), char(128), char(129)})
    for (uint32_t left = w; left > 0;) {
      uint32_t n = left < 127 ? left : 127;
      row += char(128 + n);
      row += value;
      left -= n;
    }
  std::string out = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(h) + " +X " +
                    std::to_string(w) + "\n";
  out.reserve(out.size() + row.size() * h);
  for (uint32_t y = 0; y < h; ++y)
    out += row;
  return out;
}

}  // namespace raylane::testing
