#include "raylane/core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "raylane/core/strings.h"

namespace raylane {

namespace {

namespace fs = std::filesystem;

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

}  // namespace

Status check_writable(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return Error{"it is a directory"};
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  if (!fs::is_directory(dir, ec)) {
    bool exists = fs::exists(dir, ec);
    // The whole path, not in_quotes' shortened token: the folder is what the user must find.
    return Error{cat("'", dir.string(), exists ? "' is not a folder" : "': no such folder")};
  }
  std::string probe = temp_path_for(path);
  std::FILE* f = std::fopen(probe.c_str(), "wbx");
  if (!f)
    return Error{cat("cannot create a file in ", in_quotes(dir.string()), ": ", errno_text())};
  std::fclose(f);
  std::remove(probe.c_str());
  return ok_status();
}

Status write_file_atomically(const std::string& path,
                             const std::function<Status(std::FILE*)>& write) {
  if (Status s = check_writable(path); !s) return s;
  std::string temp = temp_path_for(path);
  std::FILE* f = std::fopen(temp.c_str(), "wbx");
  if (!f) return Error{cat("cannot create ", in_quotes(temp), ": ", errno_text())};
  Status s = write(f);
  bool flushed = std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  bool closed = std::fclose(f) == 0;
  if (s && !(flushed && closed)) s = Error{cat("write failed: ", errno_text())};
  if (s && std::rename(temp.c_str(), path.c_str()) != 0)
    s = Error{cat("rename failed: ", errno_text())};
  if (!s) std::remove(temp.c_str());
  return s;
}

Status write_file_atomically(const std::string& path, const std::string& bytes) {
  return write_file_atomically(path, [&](std::FILE* f) -> Status {
    if (std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size())
      return Error{cat("write failed: ", errno_text())};
    return ok_status();
  });
}

}  // namespace raylane
