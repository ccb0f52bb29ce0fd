#include "file_roles.h"

#include <sys/stat.h>

#include <deque>
#include <filesystem>

#include "raylane/core/strings.h"

namespace raylane::cli {

namespace {

namespace fs = std::filesystem;

// The kernel's own limit on links followed in one lookup (Linux's MAXSYMLINKS, ELOOP).
constexpr int kMaxLinks = 40;

std::deque<fs::path> components_of(const fs::path& p) {
  std::deque<fs::path> parts;
  for (const fs::path& part : p.relative_path())
    parts.push_back(part);
  return parts;
}

}  // namespace

// The walk path resolution does (path_resolution(7)), done by hand so that it goes on where
// the file does not exist yet: every component that is a link is replaced by its target
// (absolute targets restart at the root, relative ones are read in the link's folder), and
// `..` steps out of the folder reached so far, which holds no links any more. A dangling link
// therefore leads to the file a write through it would create.
std::string final_target(const std::string& path) {
  std::error_code ec;
  fs::path start = fs::absolute(path, ec);
  if (ec) return path;
  fs::path reached = start.root_path();
  std::deque<fs::path> rest = components_of(start);
  for (int links = 0; !rest.empty();) {
    fs::path part = std::move(rest.front());
    rest.pop_front();
    if (part.empty() || part == ".") continue;
    if (part == "..") {
      reached = reached.parent_path();
      continue;
    }
    fs::path next = reached / part;
    if (!fs::is_symlink(fs::symlink_status(next, ec))) {
      reached = std::move(next);
      continue;
    }
    fs::path to = fs::read_symlink(next, ec);
    if (ec || ++links > kMaxLinks) return path;  // a loop: opening it fails, nothing is written
    std::deque<fs::path> inner = components_of(to);
    rest.insert(rest.begin(), inner.begin(), inner.end());
    if (to.is_absolute()) reached = to.root_path();
  }
  return reached.string();
}

bool same_file(const std::string& a, const std::string& b) {
  std::string ta = final_target(a), tb = final_target(b);
  struct stat sa {
  }, sb{};
  bool a_exists = ::stat(ta.c_str(), &sa) == 0, b_exists = ::stat(tb.c_str(), &sb) == 0;
  if (a_exists && b_exists) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (a_exists || b_exists) return false;
  return ta == tb;
}

Status check_outputs_apart(const std::vector<FileRole>& inputs,
                           const std::vector<FileRole>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const FileRole& out = outputs[i];
    for (const FileRole& in : inputs)
      if (same_file(out.path, in.path))
        return Error{cat(out.role, " ", quote_path(out.path), " is ", in.role, " ",
                         quote_path(in.path), ": writing it would destroy an input")};
    for (std::size_t j = 0; j < i; ++j)
      if (same_file(out.path, outputs[j].path))
        return Error{cat(out.role, " ", quote_path(out.path), " and ", outputs[j].role, " ",
                         quote_path(outputs[j].path), " are one file")};
  }
  return ok_status();
}

}  // namespace raylane::cli
