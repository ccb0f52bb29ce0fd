// The default image memory (core/memory.h): half of what this process can have, within its
// limits, so that the assets desktop renderers load every day load by default.
#include "raylane/core/memory.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "raylane/core/limits.h"

namespace raylane {
namespace {

constexpr uint64_t kMiB = uint64_t(1) << 20, kGiB = uint64_t(1) << 30;

TEST(ImageMemoryDefault, IsHalfOfWhatIsAvailableAndNeverBelowTheFloor) {
  EXPECT_EQ(default_image_memory_of(22 * kGiB), 11 * kGiB);
  EXPECT_EQ(default_image_memory_of(100 * kMiB), kDefaultImageMemory);
  EXPECT_GE(default_image_memory(), kDefaultImageMemory);
}

// A 24 GiB desktop with 20 GiB available holds a 16384x8192 HDR sky (2.5 GiB with its sampling
// tables: docs/scene-language.md, "Image memory") and twenty 4096² textures (64 MiB each).
TEST(ImageMemoryDefault, ADesktopHoldsA16kSkyAndTwenty4kTextures) {
  uint64_t sky = uint64_t(16384) * 8192 * (4 + 16), textures = 20 * 4096 * 4096 * uint64_t(4);
  EXPECT_GE(default_image_memory_of(20 * kGiB), sky + textures);
}

uint64_t vm_size() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmSize:", 0) == 0) return std::strtoull(line.c_str() + 7, nullptr, 10) * 1024;
  return 0;
}

// Under `ulimit -v`, what is available is what the limit leaves beside what the process holds.
// (default_image_memory() is computed once per process; the rule is default_image_memory_of.)
TEST(ImageMemoryDefault, FollowsUlimitV) {
  EXPECT_EXIT(
      {
        rlimit lim{};
        lim.rlim_cur = lim.rlim_max = vm_size() + 1000 * kMiB;
        if (setrlimit(RLIMIT_AS, &lim) != 0) std::exit(3);
        MemoryRoom room = memory_available();
        uint64_t image = default_image_memory_of(room.bytes);
        bool ok = room.bytes <= 1000 * kMiB && room.bytes > 900 * kMiB &&
                  room.limited_by == "ulimit -v" && image > 450 * kMiB && image <= 500 * kMiB;
        std::exit(ok ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace raylane
