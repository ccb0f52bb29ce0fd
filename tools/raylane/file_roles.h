// Outputs never eat inputs: before any work, every file a command will write is compared with
// every file it reads and with the other outputs, by identity (device and inode, links
// followed) rather than by spelling, so `scene.hdr` and `./dir/../scene.hdr` are one file.
#pragma once

#include <string>
#include <vector>

#include "raylane/core/error.h"

namespace raylane::cli {

struct FileRole {
  std::string path;
  std::string role;  // how the user named it: "the scene file", "-o", "--checkpoint", ...
};

// Whether two paths name one file: by identity when both exist, by their normalised absolute
// paths when neither does (two outputs not yet written), never when only one exists.
bool same_file(const std::string& a, const std::string& b);

// A usage error naming the first output that is an input or another output.
Status check_outputs_apart(const std::vector<FileRole>& inputs,
                           const std::vector<FileRole>& outputs);

}  // namespace raylane::cli
