#include "raylane/core/memory.h"

#include <sys/resource.h>
#include <sys/sysinfo.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>

#include "raylane/core/limits.h"
#include "raylane/core/strings.h"

namespace raylane {

namespace {

// A field of /proc/self/status in bytes ("VmSize:   1234 kB"), 0 if it cannot be read.
uint64_t status_bytes(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  std::size_t n = std::strlen(field);
  while (std::getline(in, line))
    if (line.compare(0, n, field) == 0 && line.size() > n && line[n] == ':')
      return std::strtoull(line.c_str() + n + 1, nullptr, 10) * 1024;
  return 0;
}

// What the limit `resource` leaves beside `held`; nothing to say if it is unlimited.
void take_limit(MemoryRoom& room, int resource, uint64_t held, const char* name) {
  rlimit lim{};
  if (getrlimit(resource, &lim) != 0 || lim.rlim_cur == RLIM_INFINITY) return;
  uint64_t left = lim.rlim_cur > held ? lim.rlim_cur - held : 0;
  if (left < room.bytes) room = {left, name};
}

// A field of /proc/meminfo in bytes ("MemAvailable:   1234 kB"), or nothing.
std::optional<uint64_t> meminfo_bytes(const char* field) {
  std::ifstream in("/proc/meminfo");
  std::string line;
  std::size_t n = std::strlen(field);
  while (std::getline(in, line))
    if (line.compare(0, n, field) == 0 && line.size() > n && line[n] == ':')
      return std::strtoull(line.c_str() + n + 1, nullptr, 10) * 1024;
  return std::nullopt;
}

void take_limits(MemoryRoom& room) {
  take_limit(room, RLIMIT_AS, status_bytes("VmSize"), "ulimit -v");
  take_limit(room, RLIMIT_DATA, status_bytes("VmData"), "ulimit -d");
}

}  // namespace

MemoryRoom memory_available() {
  MemoryRoom room{UINT64_MAX, "the machine's available memory"};
  struct sysinfo si {};
  bool have_si = sysinfo(&si) == 0;
  std::optional<uint64_t> ram = meminfo_bytes("MemAvailable");
  if (!ram && have_si) ram = (uint64_t(si.freeram) + si.bufferram) * si.mem_unit;
  std::optional<uint64_t> swap = meminfo_bytes("SwapFree");
  if (!swap && have_si) swap = uint64_t(si.freeswap) * si.mem_unit;
  if (ram) room.bytes = *ram + swap.value_or(0);
  take_limits(room);
  return room;
}

uint64_t default_image_memory_of(uint64_t available) {
  return std::max(available / 2, kDefaultImageMemory);
}

uint64_t default_image_memory() {
  static const uint64_t bytes = default_image_memory_of(memory_available().bytes);
  return bytes;
}

MemoryRoom memory_room() {
  MemoryRoom room{UINT64_MAX, "the machine's memory"};
  struct sysinfo si {};
  if (sysinfo(&si) == 0) room.bytes = (uint64_t(si.totalram) + si.totalswap) * si.mem_unit;
  take_limits(room);
  return room;
}

Status check_memory(uint64_t bytes, std::string_view what) {
  MemoryRoom room = memory_room();
  if (bytes <= room.bytes) return ok_status();
  return Error{cat(what, " needs ", bytes_text(bytes), "; this process can have ",
                   bytes_text(room.bytes), " more (", room.limited_by, ")")};
}

std::string bytes_text(uint64_t bytes) {
  if (bytes < 1024) return cat(bytes, " bytes");
  char text[32];
  const char* unit = bytes < (uint64_t(1) << 30) ? "MiB" : "GiB";
  double scale = bytes < (uint64_t(1) << 30) ? double(1 << 20) : double(1 << 30);
  std::snprintf(text, sizeof text, "%.1f %s", double(bytes) / scale, unit);
  return text;
}

}  // namespace raylane
