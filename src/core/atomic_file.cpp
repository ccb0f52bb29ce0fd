#include "raylane/core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <new>

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

// Where a write to `path` lands: the end of its chain of symbolic links (a relative link read
// against the folder of the link), so that the user's link is kept and its target written;
// `path` itself when it is no link. A loop stops after 40 links, as the kernel's does (ELOOP).
fs::path write_target(const std::string& path) {
  fs::path p(path);
  std::error_code ec;
  for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
    fs::path to = fs::read_symlink(p, ec);
    if (ec) break;
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  return p;
}

// A character device (/dev/null, /dev/stdout, a terminal) cannot be replaced by a rename: it is
// written in place, and every write error is reported (/dev/full: "No space left on device").
bool written_in_place(const fs::path& target) {
  std::error_code ec;
  return fs::is_character_file(target, ec);
}

// Other targets that are no regular file are refused: a FIFO without a reader would block
// for ever, and a socket or a block device is no image file.
const char* unwritable_kind(const fs::path& target) {
  std::error_code ec;
  fs::file_status st = fs::status(target, ec);
  if (ec || !fs::exists(st)) return nullptr;
  if (fs::is_fifo(st)) return "a FIFO";
  if (fs::is_socket(st)) return "a socket";
  if (fs::is_block_file(st)) return "a block device";
  return nullptr;
}

// The writer's status; memory that runs out while it encodes is a failed write like a full
// disk (the caller removes the temporary file and tries elsewhere), not an exception that
// leaves the temporary file behind.
Status run_writer(const std::function<Status(std::FILE*)>& write, std::FILE* f) {
  try {
    return write(f);
  } catch (const std::bad_alloc&) {
    return Error{"out of memory while encoding it"};
  }
}

Status write_in_place(const fs::path& target, const std::function<Status(std::FILE*)>& write) {
  std::FILE* f = std::fopen(target.c_str(), "wb");
  if (!f) return Error{cat("cannot open ", in_quotes(target.string()), ": ", errno_text())};
  Status s = run_writer(write, f);
  bool flushed = std::fflush(f) == 0;
  bool closed = std::fclose(f) == 0;
  if (s && !(flushed && closed)) s = Error{cat("write failed: ", errno_text())};
  return s;
}

}  // namespace

Status check_writable(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return Error{"it is a directory"};
  fs::path target = write_target(path);
  if (written_in_place(target)) return ok_status();
  if (const char* kind = unwritable_kind(target))
    return Error{cat("it is ", kind, ", not a regular file")};
  fs::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  if (!fs::is_directory(dir, ec)) {
    bool exists = fs::exists(dir, ec);
    // The whole path, not in_quotes' shortened token: the folder is what the user must find.
    return Error{cat("'", dir.string(), exists ? "' is not a folder" : "': no such folder")};
  }
  std::string probe = temp_path_for(target.string());
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
  fs::path target = write_target(path);
  if (written_in_place(target)) return write_in_place(target, write);
  std::string temp = temp_path_for(target.string());
  std::FILE* f = std::fopen(temp.c_str(), "wbx");
  if (!f) return Error{cat("cannot create ", in_quotes(temp), ": ", errno_text())};
  Status s = run_writer(write, f);
  bool flushed = std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  bool closed = std::fclose(f) == 0;
  if (s && !(flushed && closed)) s = Error{cat("write failed: ", errno_text())};
  if (s && std::rename(temp.c_str(), target.c_str()) != 0)
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
