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

// Where a path leads: absolute, every link on the way followed (a dangling one too, to the
// file a write through it would create), every `.` and `..` taken as the kernel takes them.
// The path unchanged where its links loop.
std::string final_target(const std::string& path);

// Whether two paths name one file: their final targets compared by identity (device and
// inode) when both exist, by spelling when neither does (two outputs not yet written, or a
// link not yet written through), never when only one exists.
bool same_file(const std::string& a, const std::string& b);

// A usage error naming the first output that is an input or another output.
Status check_outputs_apart(const std::vector<FileRole>& inputs,
                           const std::vector<FileRole>& outputs);

}  // namespace raylane::cli
