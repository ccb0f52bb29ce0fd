// How much more memory this process can have, so that an allocation whose size an input
// announces (a film, the AOVs, a texture, an environment) is refused before it is made, with a
// message naming what did not fit and how much it needed, never ended by std::bad_alloc.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "raylane/core/error.h"

namespace raylane {

// The bytes this process may still allocate: the least of the machine's memory (RAM and swap)
// and what `ulimit -v` (RLIMIT_AS) and `ulimit -d` (RLIMIT_DATA) leave beside what it already
// holds; `limited_by` says which one it is, in the user's words.
struct MemoryRoom {
  uint64_t bytes = 0;
  std::string limited_by;
};
MemoryRoom memory_room();

// The memory this process can have now: the machine's available memory (MemAvailable of
// /proc/meminfo: free RAM and the caches the kernel can drop; sysinfo's free RAM where it cannot
// be read) and free swap, within what `ulimit -v` and `ulimit -d` leave.
MemoryRoom memory_available();

// The image memory a command has when --image-memory is not given (docs/scene-language.md,
// "Image memory"): half of memory_available() when the command first asks, leaving the other
// half to the film, the tables and the BVH; never below kDefaultImageMemory (core/limits.h),
// which a machine that cannot have it refuses through check_memory anyway.
uint64_t default_image_memory();
// The same rule for `available` bytes.
uint64_t default_image_memory_of(uint64_t available);

// An error unless `bytes` more fit in memory_room(): "WHAT needs 6.0 GiB; this process can have
// 1.2 GiB more (ulimit -v)".
Status check_memory(uint64_t bytes, std::string_view what);

// "512 bytes", "12.5 MiB", "6.0 GiB".
std::string bytes_text(uint64_t bytes);

}  // namespace raylane
