#include "image_reading.h"

#include <algorithm>
#include <filesystem>

#include "raylane/image/input_image.h"
#include "raylane/image/write_image.h"

namespace raylane::cli {

Result<Image> read_any_image(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".hdr" || ext == ".pfm" || ext == ".exr") return read_image(path);
  // The texture readers tell the format by its magic number (TGA by its name) and name the
  // path in their errors.
  return read_input_image(path);
}

}  // namespace raylane::cli
