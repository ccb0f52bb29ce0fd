#include "file_roles.h"

#include <sys/stat.h>

#include <filesystem>

#include "raylane/core/strings.h"

namespace raylane::cli {

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {
  }, sb{};
  bool a_exists = ::stat(a.c_str(), &sa) == 0, b_exists = ::stat(b.c_str(), &sb) == 0;
  if (a_exists && b_exists) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (a_exists || b_exists) return false;
  std::error_code ea, eb;
  auto ca = std::filesystem::weakly_canonical(std::filesystem::absolute(a), ea);
  auto cb = std::filesystem::weakly_canonical(std::filesystem::absolute(b), eb);
  return !ea && !eb && ca == cb;
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
