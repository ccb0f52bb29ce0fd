// Writing the result of a long render so it is never lost: if the requested file cannot be
// written (a folder removed, a disk full, a permission changed while rendering), the image
// goes to a fallback file whose path the caller prints (docs/scene-language.md, "Output").
#pragma once

#include <string>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/image/image.h"
#include "raylane/image/write_image.h"

namespace raylane {

struct SavedImage {
  std::string path;          // where the image is now
  bool is_fallback = false;  // true if `path` is a fallback file, not the one asked for
  std::string first_error;   // why the requested file could not be written (when fallback)
};

// Writes `image` to `path` (atomically, as write_image). If that fails, writes it losslessly
// as PFM to a new file `raylane-rescue-<stem>-<pid>-<n>.pfm` in the first of `fallback_dirs`
// that takes it (default: the working directory, then the system's temporary folder), never
// replacing an existing file. An error only if nothing could be written anywhere.
Result<SavedImage> write_image_or_fallback(const std::string& path, const Image& image,
                                           const WriteOptions& options = {},
                                           std::vector<std::string> fallback_dirs = {});

// Where rescue files go when no folders are named: the working directory, then the system's
// temporary folder.
std::vector<std::string> default_fallback_dirs();

// `<dir>/raylane-rescue-<stem>-<pid>-<n><extension>` for the first n that no file and no link
// holds yet (empty if none could be found): a rescue never replaces anything.
std::string fresh_rescue_name(const std::string& dir, const std::string& stem,
                              const std::string& extension);

}  // namespace raylane
