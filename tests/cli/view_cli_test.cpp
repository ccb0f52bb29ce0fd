// `raylane view` without a window: its help, its options, and the answer without a display.
// The window itself is tested end to end under Xvfb (tests/cli/view_e2e.sh).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::CliRun;
using testing::run_cli;
using testing::temp_dir;

TEST(ViewCli, HelpListsTheOptionsAndTheKeys) {
  CliRun r = run_cli("view --help", temp_dir());
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("usage: raylane view [SCENE]", 0), 0u) << r.out;
  for (std::string text : {"--set LINE", "--lenient", "--spp-limit N", "--threads N", "--pfm",
                           "--region X0,Y0,X1,Y1", "arrow keys", "right drag", "wheel", "[ ]",
                           "1..8", "V ", "S (P, Ctrl+S)", "R ", "Q, Esc", "bit for bit"})
    EXPECT_NE(r.out.find(text), std::string::npos) << text;
  CliRun top = run_cli("--help", temp_dir());
  EXPECT_NE(top.out.find("raylane view [SCENE]"), std::string::npos) << top.out;
}

TEST(ViewCli, BadOptionsAreUsageErrors) {
  for (std::string args : {"view --spp-limit 0", "view --threads -1", "view a.scn b.scn",
                           "view --frobnicate", "view --region 1,2,3", "view --region 5,0,5,9"}) {
    CliRun r = run_cli(args, temp_dir());
    EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
    EXPECT_NE(r.out.find("raylane: "), std::string::npos) << r.out;
  }
}

// CI machines have no display: the viewer says so (or, built without SDL2, that it has no
// window at all) and exits 2, without waiting for anything.
TEST(ViewCli, WithoutADisplayItSaysSoAndExits2) {
  for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER"})
    unsetenv(name);  // the child inherits this process's environment
  CliRun r = run_cli("view", temp_dir(), 60);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_TRUE(r.out.find("view needs a display") != std::string::npos ||
              r.out.find("built without SDL2") != std::string::npos)
      << r.out;
  // A display that is not there: SDL falls back to a window nobody sees, which is no display.
  setenv("DISPLAY", ":87", 1);
  CliRun gone = run_cli("view", temp_dir(), 60);
  unsetenv("DISPLAY");
  EXPECT_EQ(gone.status, 2) << gone.out;
  EXPECT_TRUE(gone.out.find("view needs a display") != std::string::npos ||
              gone.out.find("built without SDL2") != std::string::npos)
      << gone.out;
}

// An X display that cannot be opened, with no XDG_RUNTIME_DIR (ssh, containers): one line from
// raylane, no "XDG_RUNTIME_DIR not set" from SDL's Wayland attempt.
TEST(ViewCli, AnUnreachableDisplayGetsOneLineAndNoWaylandNoise) {
  for (const char* name : {"WAYLAND_DISPLAY", "SDL_VIDEODRIVER", "XDG_RUNTIME_DIR"})
    unsetenv(name);
  setenv("DISPLAY", ":87", 1);
  CliRun r = run_cli("view", temp_dir(), 60);
  unsetenv("DISPLAY");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_EQ(r.out.find("XDG_RUNTIME_DIR"), std::string::npos) << r.out;
  if (r.out.find("built without SDL2") == std::string::npos) {
    EXPECT_EQ(r.out.rfind("raylane: view needs a display", 0), 0u) << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  }
}

}  // namespace
}  // namespace raylane
