#include "raylane/image/write_image.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "raylane/core/input_file.h"
#include "raylane/core/strings.h"
#include "raylane/image/exr.h"
#include "raylane/image/pfm.h"
#include "raylane/image/png.h"
#include "raylane/image/rgbe.h"

namespace raylane {

namespace {

namespace fs = std::filesystem;

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string errno_text() {
  return std::strerror(errno);
}

Status write_contents(std::FILE* f, ImageFormat format, const Image& image,
                      const WriteOptions& options) {
  if (format == ImageFormat::kPng) return write_png(f, image, options.exposure);
  if (format == ImageFormat::kExr)
    return write_exr(f, image, options.exr_layers, {options.exr_half, options.metadata});
  std::string bytes =
      format == ImageFormat::kHdr ? encode_rgbe(image, options.metadata) : encode_pfm(image);
  if (std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size())
    return Error{cat("write failed: ", errno_text())};
  return ok_status();
}

}  // namespace

Result<ImageFormat> format_from_path(const std::string& path) {
  std::string ext = lower_extension(path);
  if (ext == ".hdr") return ImageFormat::kHdr;
  if (ext == ".pfm") return ImageFormat::kPfm;
  if (ext == ".png") return ImageFormat::kPng;
  if (ext == ".exr") return ImageFormat::kExr;
  return Error{
      cat("cannot tell the image format of ", in_quotes(path), " (use .hdr, .pfm, .png or .exr)")};
}

Status write_image(const std::string& path, const Image& image, const WriteOptions& options) {
  auto format = format_from_path(path);
  if (!format) return Error{format.error()};
  return write_file_atomically(
      path, [&](std::FILE* f) { return write_contents(f, *format, image, options); });
}

Result<Image> read_image(const std::string& path) {
  auto contents = read_input_file(path, uint64_t(4) << 30, "the image");
  if (!contents) return Error{contents.error()};
  const std::string& bytes = *contents;
  std::string ext = lower_extension(path);
  if (ext == ".hdr") {
    auto f = decode_rgbe(bytes);
    if (!f) return Error{cat(path, ": ", f.error())};
    return std::move(f->image);
  }
  if (ext == ".pfm") {
    auto image = decode_pfm(bytes);
    if (!image) return Error{cat(path, ": ", image.error())};
    return image;
  }
  if (ext == ".exr") {
    auto image = decode_exr(bytes);
    if (!image) return Error{cat("cannot read ", quote_path(path), ": ", image.error())};
    return image;
  }
  return Error{cat("cannot read ", in_quotes(path), " (raylane reads .hdr, .pfm and .exr)")};
}

}  // namespace raylane
