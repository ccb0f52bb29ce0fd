// Every file raylane reads is opened through here: it must be a regular file, because a FIFO
// or a device never ends (or blocks for ever) and a directory is no file; and it must fit the
// caller's limit, checked before anything is read or allocated.
#pragma once

#include <cstdint>
#include <string>

#include "raylane/core/error.h"

namespace raylane {

// The size of a regular file; otherwise an error saying why, without the path ("not a
// regular file (a FIFO)", "No such file or directory").
Result<uint64_t> regular_file_size(const std::string& path);

// The whole file, if it is a regular file of at most max_bytes; errors name the path and
// `what` ("the scene file", "the image").
Result<std::string> read_input_file(const std::string& path, uint64_t max_bytes,
                                    const std::string& what);

// The first `max_bytes` of a regular file (all of it if it is shorter), to know its kind before
// reading the rest; errors as read_input_file's.
Result<std::string> read_input_head(const std::string& path, uint64_t max_bytes,
                                    const std::string& what);

}  // namespace raylane
