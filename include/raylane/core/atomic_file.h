// Files written atomically: to a temporary file beside the target, flushed and synced, then
// renamed into place, so a failed run never leaves a half-written or clobbered file
// (docs/scene-language.md, "Output").
#pragma once

#include <cstdio>
#include <functional>
#include <string>

#include "raylane/core/error.h"

namespace raylane {

// Can a file be created at `path`? The folder must exist and accept a new file, and `path`
// must not be a directory. Call it before long work whose result goes there.
Status check_writable(const std::string& path);

// Writes `path` through `write`, which gets the temporary file; on any failure the
// temporary is removed and an existing `path` is left as it was. A `path` that is a symbolic
// link stays one: its target is written (atomically, beside the target). A target that is a
// character device (/dev/null) is written in place, and its write errors reported; a FIFO, a
// socket or a block device is refused.
Status write_file_atomically(const std::string& path,
                             const std::function<Status(std::FILE*)>& write);
Status write_file_atomically(const std::string& path, const std::string& bytes);

}  // namespace raylane
