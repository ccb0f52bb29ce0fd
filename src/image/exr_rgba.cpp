#include "image/exr_rgba.h"

#include <Imath/half.h>
#include <OpenEXR/Iex.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfRgbaFile.h>

#include <cstdint>
#include <cstring>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "raylane/core/strings.h"

namespace raylane::exr_detail {

namespace {

// The file's bytes as an OpenEXR input stream; reading past the end is an error, as it is
// for OpenEXR's own file stream.
class MemoryStream : public Imf::IStream {
 public:
  explicit MemoryStream(std::string_view bytes) : Imf::IStream("input.exr"), bytes_(bytes) {}

  bool read(char c[], int n) override {
    if (n < 0 || pos_ > bytes_.size() || uint64_t(n) > bytes_.size() - pos_)
      throw IEX_NAMESPACE::InputExc("unexpected end of file");
    std::memcpy(c, bytes_.data() + pos_, std::size_t(n));
    pos_ += uint64_t(n);
    return pos_ < bytes_.size();
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override { pos_ = pos; }

 private:
  std::string_view bytes_;
  uint64_t pos_ = 0;
};

// The byte size of each attribute type whose value has one (OpenEXR File Layout, "Predefined
// Attribute Types"); 0 for the types sized by their value (chlist, preview, string,
// stringvector, floatvector) and for types the library does not know (kept as opaque bytes).
uint32_t fixed_size(std::string_view type) {
  static constexpr std::pair<std::string_view, uint32_t> kSizes[] = {
      {"box2i", 16},      {"box2f", 16},   {"chromaticities", 32},
      {"compression", 1}, {"double", 8},   {"envmap", 1},
      {"float", 4},       {"int", 4},      {"keycode", 28},
      {"lineOrder", 1},   {"m33f", 36},    {"m33d", 72},
      {"m44f", 64},       {"m44d", 128},   {"rational", 8},
      {"tiledesc", 9},    {"timecode", 8}, {"v2i", 8},
      {"v2f", 8},         {"v2d", 16},     {"v3i", 12},
      {"v3f", 12},        {"v3d", 24},     {"deepImageState", 1}};
  for (const auto& [name, size] : kSizes)
    if (name == type) return size;
  return 0;
}

uint32_t little_u32(std::string_view b, std::size_t at) {
  return uint32_t(uint8_t(b[at])) | uint32_t(uint8_t(b[at + 1])) << 8 |
         uint32_t(uint8_t(b[at + 2])) << 16 | uint32_t(uint8_t(b[at + 3])) << 24;
}

// Whether a value sized by its contents fills its declared size exactly, as OpenEXR's C++
// reader parses it: a channel list's entries (a name, 16 bytes) up to an empty name; a
// preview's width and height, then 4 bytes a pixel; a string vector's strings, each a 32-bit
// length and its bytes.
bool fills_its_size(std::string_view type, std::string_view v) {
  if (type == "chlist") {
    std::size_t at = 0;
    for (;;) {
      const std::size_t end = v.find('\0', at);
      if (end == std::string_view::npos) return false;
      if (end == at) return end + 1 == v.size();
      at = end + 1 + 16;
      if (at > v.size()) return false;
    }
  }
  if (type == "preview")
    return v.size() >= 8 &&
           uint64_t(little_u32(v, 0)) * little_u32(v, 4) * 4 == uint64_t(v.size() - 8);
  if (type == "stringvector") {
    std::size_t at = 0;
    while (at < v.size()) {
      if (v.size() - at < 4 || little_u32(v, at) > v.size() - at - 4) return false;
      at += 4 + little_u32(v, at);
    }
    return true;
  }
  if (type == "floatvector") return v.size() % 4 == 0;
  return true;
}

// OpenEXR 3.1's C++ reader, which decodes these files, sizes an attribute's value by the size
// its header declares before it reads the bytes (a string is resized to it first), and reads a
// value of a known type at that type's size whatever the header declares, so that a damaged
// header reads differently to it than to OpenEXRCore (which checked the file before). A
// 461-byte file whose "compression" declared 33 bytes read to that reader as a "software"
// string of 1.9 GB, which it allocated (the image fuzzer found it). So the header is walked
// first as that reader will walk it, and refused unless every attribute's value lies within
// the file and has its type's size, or fills its declared size exactly: then what the reader
// allocates for the header is bounded by the file. The header is attributes (name and type,
// NUL-terminated, a little-endian 32-bit size, the value) up to an empty name; a multi-part
// file (version flag 0x1000) has one such header per part, ended by an empty one.
std::optional<std::string> header_problem(std::string_view bytes) {
  const std::string ends = "the EXR file ends inside its header";
  std::size_t pos = 8;  // the magic number and the version field
  if (bytes.size() < pos) return ends;
  const bool multipart = (little_u32(bytes, 4) & 0x1000u) != 0;
  auto text = [&]() -> std::optional<std::string_view> {
    const std::size_t end = bytes.find('\0', pos);
    if (end == std::string_view::npos) return std::nullopt;
    std::string_view s = bytes.substr(pos, end - pos);
    pos = end + 1;
    return s;
  };
  for (;;) {
    bool empty = true;
    for (;;) {
      const auto name = text();
      if (!name) return ends;
      if (name->empty()) break;
      empty = false;
      const auto type = text();
      if (!type || bytes.size() - pos < 4) return ends;
      const uint32_t size = little_u32(bytes, pos);
      pos += 4;
      if (size > bytes.size() - pos)
        return cat("the EXR header's attribute \"", *name, "\" declares ", size,
                   " bytes where the file has ", bytes.size() - pos, " left");
      const uint32_t fixed = fixed_size(*type);
      if ((fixed != 0 && size != fixed) || !fills_its_size(*type, bytes.substr(pos, size)))
        return cat("the EXR header's attribute \"", *name, "\" of type ", *type, " declares ", size,
                   " bytes, which its value does not fill; the header is damaged");
      pos += size;
    }
    if (!multipart || empty) return std::nullopt;
  }
}

// The data window as OpenEXR's C++ reader will read it, from the header alone: RgbaInputFile's
// constructor allocates line and chroma-filter buffers by that window's width before anything
// else can be checked, and a damaged header can read to it at another size than to OpenEXRCore
// (a duplicated "dataWindow" attribute: the core keeps one, the C++ reader the other). A file
// the fuzzer found read as 8x6 to the core and as 2^24 wide to RgbaInputFile, which then
// allocated 4 GiB. The header is read from the same bytes by the same Imf::Header::readFrom
// that RgbaInputFile's InputFile calls; header_problem() has bounded what it allocates.
std::optional<std::string> window_problem(MemoryStream& stream, std::string_view bytes,
                                          uint32_t width, uint32_t height) {
  Imf::Header header;
  int version = int(little_u32(bytes, 4));
  stream.seekg(8);  // past the magic number and the version field
  header.readFrom(stream, version);
  stream.seekg(0);  // RgbaInputFile reads from the stream's position
  const Imath::Box2i& dw = header.dataWindow();
  const int64_t w = int64_t(dw.max.x) - dw.min.x + 1, h = int64_t(dw.max.y) - dw.min.y + 1;
  if (w == int64_t(width) && h == int64_t(height)) return std::nullopt;
  return cat("the EXR header reads as ", width, "x", height, " and as ", w, "x", h,
             "; the file is damaged");
}

}  // namespace

Result<Image> decode_rgba_interface(std::string_view bytes, uint32_t width, uint32_t height) {
  if (auto bad = header_problem(bytes)) return Error{*bad};
  try {
    MemoryStream stream(bytes);
    if (auto bad = window_problem(stream, bytes, width, height)) return Error{*bad};
    Imf::RgbaInputFile file(stream);
    const Imath::Box2i& dw = file.dataWindow();
    const std::size_t w = std::size_t(dw.max.x - dw.min.x + 1);
    const std::size_t h = std::size_t(dw.max.y - dw.min.y + 1);
    std::vector<Imf::Rgba> rows(w * h);
    // The frame buffer is addressed by absolute pixel coordinates: shift it by the window's
    // corner (OpenEXR's documented idiom, "Reading an RGBA Image File"). The shifted address
    // lies outside the rows wherever the corner is not (0, 0): computed as an integer, since
    // pointer arithmetic past an array is undefined (UBSan found a window at negative
    // coordinates); OpenEXR adds the offsets back before it writes.
    const std::ptrdiff_t shift =
        std::ptrdiff_t(dw.min.x) + std::ptrdiff_t(dw.min.y) * std::ptrdiff_t(w);
    auto* origin = reinterpret_cast<Imf::Rgba*>(reinterpret_cast<std::uintptr_t>(rows.data()) -
                                                std::uintptr_t(shift) * sizeof(Imf::Rgba));
    file.setFrameBuffer(origin, 1, w);
    file.readPixels(dw.min.y, dw.max.y);
    Image img;
    img.width = uint32_t(w), img.height = uint32_t(h);
    img.rgb.resize(w * h * 3);
    for (std::size_t i = 0; i < w * h; ++i) {
      img.rgb[3 * i] = float(rows[i].r);
      img.rgb[3 * i + 1] = float(rows[i].g);
      img.rgb[3 * i + 2] = float(rows[i].b);
    }
    return img;
  } catch (const std::exception& e) {
    return Error{cat("cannot decode the EXR luminance-chroma image: ", e.what())};
  }
}

}  // namespace raylane::exr_detail
