#include "raylane/core/memory.h"

#include <sys/resource.h>
#include <sys/sysinfo.h>

#include <cstdio>
#include <cstring>
#include <fstream>

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

}  // namespace

MemoryRoom memory_room() {
  MemoryRoom room{UINT64_MAX, "the machine's memory"};
  struct sysinfo si {};
  if (sysinfo(&si) == 0) room.bytes = (uint64_t(si.totalram) + si.totalswap) * si.mem_unit;
  take_limit(room, RLIMIT_AS, status_bytes("VmSize"), "ulimit -v");
  take_limit(room, RLIMIT_DATA, status_bytes("VmData"), "ulimit -d");
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
