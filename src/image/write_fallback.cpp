#include "raylane/image/write_fallback.h"

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "raylane/core/strings.h"

namespace raylane {

namespace fs = std::filesystem;

std::vector<std::string> default_fallback_dirs() {
  std::vector<std::string> dirs{"."};
  std::error_code ec;
  fs::path tmp = fs::temp_directory_path(ec);
  if (!ec) dirs.push_back(tmp.string());
  return dirs;
}

// write_image renames over an existing file and writes through a link (a dangling one too),
// so a name is free only when nothing at all holds it.
std::string fresh_rescue_name(const std::string& dir, const std::string& stem,
                              const std::string& extension) {
  std::error_code ec;
  for (int n = 0;; ++n) {
    fs::path p = fs::path(dir) / cat("raylane-rescue-", stem, "-", ::getpid(), "-", n, extension);
    // symlink_status sets `ec` for a name that is free; only not_found means free.
    if (fs::symlink_status(p, ec).type() == fs::file_type::not_found) return p.string();
    if (ec || n > 1000) return {};
  }
}

Result<SavedImage> write_image_or_fallback(const std::string& path, const Image& image,
                                           const WriteOptions& options,
                                           std::vector<std::string> fallback_dirs) {
  Status first = write_image(path, image, options);
  if (first) return SavedImage{path, false, {}};
  if (fallback_dirs.empty()) fallback_dirs = default_fallback_dirs();
  std::string stem = fs::path(path).stem().string();
  if (stem.empty()) stem = "image";
  std::string errors = cat(path, ": ", first.error());
  for (const auto& dir : fallback_dirs) {
    std::string candidate = fresh_rescue_name(dir, stem, ".pfm");
    if (candidate.empty()) continue;
    // PFM: lossless floats, and no encoder that could fail where the first format did.
    Status s = write_image(candidate, image, options);
    if (s) return SavedImage{candidate, true, first.error()};
    errors += cat("; ", candidate, ": ", s.error());
  }
  return Error{cat("the image could not be written anywhere (", errors, ")")};
}

}  // namespace raylane
