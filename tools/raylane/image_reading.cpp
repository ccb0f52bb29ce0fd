#include "image_reading.h"

#include <algorithm>
#include <filesystem>

#include "raylane/core/input_file.h"
#include "raylane/core/strings.h"
#include "raylane/image/input_image.h"
#include "raylane/image/write_image.h"

namespace raylane::cli {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

bool is_own_format(const std::string& path) {
  std::string ext = lower_extension(path);
  return ext == ".hdr" || ext == ".pfm" || ext == ".exr";
}

}  // namespace

Result<ImageHeader> read_any_header(const std::string& path) {
  // The header alone: a file is read whole only when its first bytes do not hold the header.
  auto info = read_input_image_info(path, UINT64_MAX);
  if (!info) {
    // An EXR's errors read as its reader's always have: "cannot read 'x.exr': ...".
    std::string why = info.error(), prefix = path + ": ";
    if (why.rfind(prefix, 0) == 0 && lower_extension(path) == ".exr")
      return Error{cat("cannot read ", quote_path(path), ": ", why.substr(prefix.size()))};
    return Error{why};
  }
  auto size = regular_file_size(path);
  if (!size) return Error{cat(path, ": ", size.error())};
  ImageHeader h{path, info->width, info->height, 0, *size};
  h.decode = decode_bytes(*info, *size);
  return h;
}

Status check_images_memory(const std::vector<ImageHeader>& images, uint64_t after,
                           const ImageMemoryOption& memory) {
  uint64_t kept = 0, total = 0;
  for (const ImageHeader& h : images) {
    total = std::max(total, kept + h.decode);
    kept += h.float_bytes();
  }
  total = std::max(total, kept + after);
  for (const ImageHeader& h : images) {
    std::string what = cat("decoding its ", h.width, "x", h.height, " pixels");
    if (!memory.chosen)
      if (auto bomb = decode_ratio_error(h.decode, h.file_bytes, total, what))
        return Error{cat(h.path, ": ", *bomb)};
  }
  if (total > memory.bytes)
    return Error{cat("reading ", images.size() == 1 ? "the image" : "the images", " takes ",
                     bytes_text(total), "; the image memory is ", bytes_text(memory.bytes),
                     ": --image-memory ", image_memory_mib(total), " reads ",
                     images.size() == 1 ? "it" : "them")};
  return check_memory(total, "reading the images");
}

Result<Image> read_any_image(const ImageHeader& h) {
  // raylane's outputs may hold any float (an AOV's negative normals, a NaN a diff must count);
  // the texture reader refuses those, so they go to the output formats' readers. Their memory
  // was checked from the header above.
  if (is_own_format(h.path)) return read_image(h.path);
  // The texture readers tell the format by its magic number (TGA by its name) and name the
  // path in their errors.
  return read_input_image(h.path, UINT64_MAX, true);
}

}  // namespace raylane::cli
