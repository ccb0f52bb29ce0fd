#include "support/paths.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

namespace raylane::testing {

namespace fs = std::filesystem;

std::string source_path(const std::string& relative) {
  return std::string(RAYLANE_SOURCE_DIR) + "/" + relative;
}

std::string cli_path() {
  return RAYLANE_CLI_PATH;
}

namespace {
struct TempDirs {
  std::vector<fs::path> dirs;
  ~TempDirs() {
    std::error_code ec;
    for (auto& d : dirs)
      fs::remove_all(d, ec);
  }
};
}  // namespace

std::string temp_dir() {
  static TempDirs all;
  static std::atomic<int> counter{0};
  std::string name = "raylane-test-";
  if (auto* info = ::testing::UnitTest::GetInstance()->current_test_info())
    name += std::string(info->test_suite_name()) + "-" + info->name() + "-";
  name += std::to_string(::getpid()) + "-" + std::to_string(counter++);
  fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  all.dirs.push_back(dir);
  return dir.string();
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string dir_with_scene(const std::string& scene) {
  std::string dir = temp_dir();
  write_file(dir + "/s.scn", scene);
  return dir;
}

}  // namespace raylane::testing
