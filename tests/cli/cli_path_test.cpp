// `raylane render` in path mode and `raylane convert`, as a user runs them: flags, identical
// files for any thread count, Ctrl-C writing the image (and checkpoint) so far with exit
// status 130, resuming a checkpoint.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "raylane/image/write_image.h"
#include "support/paths.h"

extern char** environ;

namespace raylane {
namespace {

using testing::cli_path;
using testing::source_path;
using testing::temp_dir;

int run_status(const std::string& args) {
  std::string cmd = "'" + cli_path() + "' " + args + " >/dev/null 2>&1";
  int st = std::system(cmd.c_str());
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(CliPath, BadPathFlagsExitTwo) {
  std::string dir = temp_dir();
  EXPECT_EQ(run_status("render --spp 0 -o " + dir + "/a.hdr"), 2);
  EXPECT_EQ(run_status("render --integrator bidir -o " + dir + "/a.hdr"), 2);
  EXPECT_EQ(run_status("render --time -1 -o " + dir + "/a.hdr"), 2);
  EXPECT_EQ(run_status("render --seed x -o " + dir + "/a.hdr"), 2);
  EXPECT_EQ(run_status("render --traversal sideways -o " + dir + "/a.hdr"), 2);
  EXPECT_FALSE(std::filesystem::exists(dir + "/a.hdr"));
  EXPECT_EQ(run_status("convert only-one.hdr"), 2);
  EXPECT_EQ(run_status("convert missing.hdr " + dir + "/b.png"), 2);
}

TEST(CliPath, FilesAreIdenticalForAnyThreadCountAndConvert) {
  std::string dir = temp_dir(), scene = source_path("scenes/sphere.scn");
  ASSERT_EQ(run_status("render " + scene + " --spp 2 --threads 1 -o " + dir + "/one.hdr"), 0);
  ASSERT_EQ(run_status("render " + scene + " --spp 2 --threads 2 -o " + dir + "/two.hdr"), 0);
  ASSERT_EQ(run_status("render " + scene + " --spp 2 --seed 1 -o " + dir + "/seed1.hdr"), 0);
  std::string one = read_file(dir + "/one.hdr");
  EXPECT_GT(one.size(), 100u);
  EXPECT_EQ(one, read_file(dir + "/two.hdr"));
  EXPECT_NE(one, read_file(dir + "/seed1.hdr"));
  EXPECT_NE(one.find("RAYLANE_SPP=2"), std::string::npos);
  ASSERT_EQ(run_status("convert " + dir + "/one.hdr " + dir + "/one.pfm"), 0);
  auto a = read_image(dir + "/one.hdr"), b = read_image(dir + "/one.pfm");
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->rgb, b->rgb);  // RGBE values are exact in float
}

// The first SIGINT ends the render after the pass in flight: a valid image with the samples
// taken so far in its header, and exit status 130; the --checkpoint film is saved then too,
// and resuming it gives exactly the file of an uninterrupted render (docs/design.md,
// "Determinism").
TEST(CliPath, SigintWritesTheImageAndCheckpointSoFarAndExits130) {
  std::string dir = temp_dir(), out = dir + "/int.hdr", exe = cli_path();
  std::string scene = source_path("scenes/testscene.scn"), film = dir + "/int.film";
  std::vector<std::string> args = {exe,
                                   "render",
                                   scene,
                                   "--spp",
                                   "1000000",
                                   "--quiet",
                                   "-o",
                                   out,
                                   "--checkpoint",
                                   film,
                                   "--checkpoint-every",
                                   "1000"};
  std::vector<char*> argv;
  for (auto& a : args)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid;
  ASSERT_EQ(posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv.data(), environ), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int st = 0;
  ASSERT_EQ(waitpid(pid, &st, 0), pid);
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 130);
  auto img = read_image(out);
  ASSERT_TRUE(img.ok()) << img.error();
  EXPECT_EQ(img->width, 400u);
  std::string text = read_file(out);
  auto at = text.find("RAYLANE_SPP=");
  ASSERT_NE(at, std::string::npos);
  int spp = std::atoi(text.c_str() + at + 12);
  EXPECT_GE(spp, 1);
  EXPECT_LT(spp, 1000000);

  // The film holds those passes; two more from it equal one uninterrupted render.
  std::string more = std::to_string(spp + 2);
  ASSERT_EQ(run_status("render " + scene + " --spp " + more + " --resume " + film + " -o " + dir +
                       "/resumed.hdr"),
            0);
  ASSERT_EQ(run_status("render " + scene + " --spp " + more + " -o " + dir + "/whole.hdr"), 0);
  std::string resumed = read_file(dir + "/resumed.hdr");
  EXPECT_NE(resumed.find("RAYLANE_SPP=" + more), std::string::npos);
  EXPECT_EQ(resumed, read_file(dir + "/whole.hdr"));
  // A film is only continued with the settings that made it.
  EXPECT_EQ(run_status("render " + scene + " --spp " + more + " --seed 9 --resume " + film +
                       " -o " + dir + "/other.hdr"),
            2);
  EXPECT_FALSE(std::filesystem::exists(dir + "/other.hdr"));
}

}  // namespace
}  // namespace raylane
