// libFuzzer target: bytes → Radiance RGBE image or an error. A decoded image must have
// exactly width·height pixels, and re-encoding it must decode to the same size.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "raylane/image/rgbe.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  auto file = raylane::decode_rgbe(bytes);
  if (!file) return 0;
  const raylane::Image& image = file->image;
  if (image.rgb.size() != std::size_t(image.width) * image.height * 3) std::abort();
  auto again = raylane::decode_rgbe(raylane::encode_rgbe(image));
  if (!again || again->image.width != image.width || again->image.height != image.height)
    std::abort();
  return 0;
}
