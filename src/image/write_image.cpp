#include "raylane/image/write_image.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "raylane/core/strings.h"
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

// A unique name beside `path`: `.name.tmp-<pid>-<n>`.
std::string temp_path_for(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  fs::path p(path);
  return (p.parent_path() /
          cat(".", p.filename().string(), ".tmp-", ::getpid(), "-", counter.fetch_add(1)))
      .string();
}

std::string errno_text() {
  return std::strerror(errno);
}

Status write_contents(std::FILE* f, ImageFormat format, const Image& image,
                      const WriteOptions& options) {
  if (format == ImageFormat::kPng) return write_png(f, image, options.exposure);
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
  return Error{
      cat("cannot tell the image format of ", in_quotes(path), " (use .hdr, .pfm or .png)")};
}

Status check_writable(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return Error{"it is a directory"};
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  if (!fs::is_directory(dir, ec))
    return Error{cat("folder ", in_quotes(dir.string()), " does not exist")};
  std::string probe = temp_path_for(path);
  std::FILE* f = std::fopen(probe.c_str(), "wbx");
  if (!f)
    return Error{cat("cannot create a file in ", in_quotes(dir.string()), ": ", errno_text())};
  std::fclose(f);
  std::remove(probe.c_str());
  return ok_status();
}

Status write_image(const std::string& path, const Image& image, const WriteOptions& options) {
  auto format = format_from_path(path);
  if (!format) return Error{format.error()};
  if (Status s = check_writable(path); !s) return s;
  std::string temp = temp_path_for(path);
  std::FILE* f = std::fopen(temp.c_str(), "wbx");
  if (!f) return Error{cat("cannot create ", in_quotes(temp), ": ", errno_text())};
  Status s = write_contents(f, *format, image, options);
  bool flushed = std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  bool closed = std::fclose(f) == 0;
  if (s && !(flushed && closed)) s = Error{cat("write failed: ", errno_text())};
  if (s && std::rename(temp.c_str(), path.c_str()) != 0)
    s = Error{cat("rename failed: ", errno_text())};
  if (!s) std::remove(temp.c_str());
  return s;
}

Result<Image> read_image(const std::string& path) {
  std::error_code ec;
  auto size = fs::file_size(path, ec);
  if (ec) return Error{cat("cannot read ", in_quotes(path), ": ", ec.message())};
  if (size > (uint64_t(4) << 30)) return Error{"image file is over 4 GiB"};
  std::ifstream in(path, std::ios::binary);
  std::ostringstream buf;
  buf << in.rdbuf();
  std::string bytes = buf.str();
  std::string ext = lower_extension(path);
  if (ext == ".hdr") {
    auto f = decode_rgbe(bytes);
    if (!f) return Error{f.error()};
    return std::move(f->image);
  }
  if (ext == ".pfm") return decode_pfm(bytes);
  return Error{cat("cannot read ", in_quotes(path), " (raylane reads .hdr and .pfm)")};
}

}  // namespace raylane
