#include "raylane/core/input_file.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "raylane/core/strings.h"

namespace raylane {

namespace {
const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}
}  // namespace

Result<uint64_t> regular_file_size(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return Error{std::strerror(errno)};
  if (!S_ISREG(st.st_mode)) return Error{cat("not a regular file (", kind_of(st.st_mode), ")")};
  return uint64_t(st.st_size);
}

Result<std::string> read_input_file(const std::string& path, uint64_t max_bytes,
                                    const std::string& what) {
  auto size = regular_file_size(path);
  if (!size) return Error{cat(path, ": cannot read ", what, ": ", size.error())};
  if (*size > max_bytes)
    return Error{cat(path, ": ", what, " has ", *size, " bytes; ", max_bytes, " at most")};
  std::ifstream in(path, std::ios::binary);
  std::string bytes(*size, '\0');
  if (!in.read(bytes.data(), std::streamsize(bytes.size())))
    return Error{cat(path, ": cannot read ", what, ": read failed")};
  return bytes;
}

Result<std::string> read_input_head(const std::string& path, uint64_t max_bytes,
                                    const std::string& what) {
  auto size = regular_file_size(path);
  if (!size) return Error{cat(path, ": cannot read ", what, ": ", size.error())};
  std::ifstream in(path, std::ios::binary);
  std::string bytes(std::min(*size, max_bytes), '\0');
  if (!in.read(bytes.data(), std::streamsize(bytes.size())))
    return Error{cat(path, ": cannot read ", what, ": read failed")};
  return bytes;
}

}  // namespace raylane
