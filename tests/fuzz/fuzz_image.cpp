// libFuzzer target: bytes → a texture or environment image (every format raylane reads) or an
// error. The first byte picks the file name (odd: "input.tga", since TGA is known by its
// extension alone); the rest is the file. A decoded image must have the size its header
// announced, within the pixel limit, and hold only finite values >= 0. An EXR's layers are
// decoded too, each to the size of its channels.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "raylane/image/exr.h"
#include "raylane/image/input_image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  std::string_view name = (data[0] & 1) ? "input.tga" : "input";
  std::string_view bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  if (raylane::is_exr(bytes)) {
    auto exr = raylane::probe_exr(bytes);
    for (const std::string& layer : exr ? exr->layers : std::vector<std::string>{}) {
      auto l = raylane::decode_exr_layer(bytes, layer);
      if (l && l->data.size() != std::size_t(exr->width) * exr->height * l->channels.size())
        std::abort();
    }
  }
  auto info = raylane::probe_input_image(bytes, name);
  auto image = raylane::decode_input_image(bytes, name, raylane::kDefaultImageMemory);
  if (!image) return 0;
  // The compact texels a scene keeps decode to exactly the float image (image/texels.h), palette
  // BMPs included: one whose indices point past its palette is refused before stb reads its
  // uninitialised palette entries (src/image/bmp_palette.cpp).
  auto texels = raylane::decode_input_texels(bytes, name, raylane::kDefaultImageMemory);
  if (texels && raylane::to_float_image(*texels).rgb != image->rgb) std::abort();
  if (!info) std::abort();  // decoding succeeded where probing failed
  if (image->width != info->width || image->height != info->height) std::abort();
  if (uint64_t(image->width) * image->height > raylane::kMaxImagePixels) std::abort();
  if (image->rgb.size() != std::size_t(image->width) * image->height * 3) std::abort();
  for (float v : image->rgb)
    if (!(v >= 0) || !std::isfinite(v)) std::abort();
  return 0;
}
