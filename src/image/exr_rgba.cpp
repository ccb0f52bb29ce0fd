#include "image/exr_rgba.h"

#include <Imath/half.h>
#include <OpenEXR/Iex.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfRgbaFile.h>

#include <cstdint>
#include <cstring>
#include <exception>
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

}  // namespace

Result<Image> decode_rgba_interface(std::string_view bytes) {
  try {
    MemoryStream stream(bytes);
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
