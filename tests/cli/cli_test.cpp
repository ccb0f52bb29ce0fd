// The `raylane` program as a user runs it: exit statuses, messages, files written or not.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;
using testing::cli_path;
using testing::CliRun;
using testing::source_path;
using testing::temp_dir;

// Runs the program with `args` (shell words) in `dir`.
CliRun run(const std::string& args, const std::string& dir) {
  return testing::run_cli(args, dir);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(Cli, HelpAndVersionExitZero) {
  std::string dir = temp_dir();
  CliRun help = run("--help", dir);
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("raylane render [SCENE]"), std::string::npos);
  CliRun version = run("--version", dir);
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.out.rfind("raylane ", 0), 0u);
}

// Every command answers --help and -h with its own text and exit status 0; render's lists
// every option, and each default sits on a line of its own.
TEST(Cli, EveryCommandHasHelp) {
  std::string dir = temp_dir();
  for (std::string command : {"render", "info", "trace", "convert", "diff"})
    for (std::string flag : {"--help", "-h"}) {
      CliRun r = run(command + " " + flag, dir);
      EXPECT_EQ(r.status, 0) << command << " " << flag;
      EXPECT_EQ(r.out.rfind("usage: raylane " + command, 0), 0u) << r.out;
    }
  CliRun render = run("render --help", dir);
  for (std::string option :
       {"--output FILE", "--mode MODE", "--spp N", "--integrator I", "--seed S", "--max-depth D",
        "--time SECONDS", "--checkpoint FILE", "--checkpoint-every SECONDS", "--resume FILE",
        "--png", "--exposure E", "--threads N", "--tracer T", "--isa I", "--lenient", "--quiet"})
    EXPECT_NE(render.out.find(option), std::string::npos) << option;
  EXPECT_NE(render.out.find("\n                      (default: 60)\n"), std::string::npos)
      << render.out;  // --checkpoint-every's default, on its own line under it
  EXPECT_EQ(render.out.find("traversal"), std::string::npos) << render.out;
}

TEST(Cli, UsageErrorsExitTwo) {
  std::string dir = temp_dir();
  EXPECT_EQ(run("render --bogus", dir).status, 2);
  EXPECT_EQ(run("frobnicate", dir).status, 2);
  EXPECT_EQ(run("render --mode sideways", dir).status, 2);
  EXPECT_EQ(run("render --threads -3", dir).status, 2);
  EXPECT_EQ(run("render -o out.jpg", dir).status, 2);
  CliRun r = run("render --threads", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("option --threads needs a value"), std::string::npos);
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Cli, RendersTheBuiltInSceneByDefault) {
  std::string dir = temp_dir();
  CliRun r = run("render --mode id --quiet", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "testscene.hdr\n");
  std::string hdr = read_file(dir + "/testscene.hdr");
  EXPECT_EQ(hdr.rfind("#?RADIANCE\n", 0), 0u);
  EXPECT_NE(hdr.find("-Y 300 +X 400\n"), std::string::npos);
}

TEST(Cli, BadSceneReportsEveryErrorAndWritesNothing) {
  std::string dir = temp_dir();
  fs::copy(source_path("scenes/testscene-damaged.scn"), dir + "/damaged.scn");
  fs::copy(source_path("scenes/letterX.ply"), dir + "/letterX.ply");
  fs::copy(source_path("scenes/letterY.ply"), dir + "/letterY.ply");
  CliRun r = run("render damaged.scn -o out.hdr", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("damaged.scn:6:1: brdf takes 7 or 11 numbers, found 10"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("damaged.scn:31:1: cylinder takes 7 numbers, found 6"), std::string::npos);
  EXPECT_NE(r.out.find("12 errors in the scene"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir + "/out.hdr"));
  // --lenient renders it, reporting the skipped lines as warnings.
  CliRun lenient = run("render damaged.scn --lenient --mode albedo -o out.hdr", dir);
  EXPECT_EQ(lenient.status, 0) << lenient.out;
  EXPECT_NE(lenient.out.find("warning: brdf takes 7 or 11 numbers, found 10 (line skipped)"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(dir + "/out.hdr"));
}

TEST(Cli, UnwritableOutputFailsBeforeRenderingAndKeepsExistingFiles) {
  std::string dir = temp_dir();
  CliRun r = run("render --mode id -o no/such/dir/out.hdr", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("cannot write no/such/dir/out.hdr"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("rendered"), std::string::npos);  // failed before rendering
  // An output that is a directory: an error, and the directory is untouched.
  fs::create_directory(dir + "/taken.hdr");
  EXPECT_EQ(run("render --mode id -o taken.hdr", dir).status, 2);
  EXPECT_TRUE(fs::is_directory(dir + "/taken.hdr"));
}

// Failures that hold for root too (the tests run as root in CI, where permissions do not
// stop anything): a folder that is a regular file, and a file name longer than NAME_MAX.
// Each is an error before rendering, and the existing file is untouched.
TEST(Cli, OutputThatFailsEvenForRootIsAnErrorBeforeRendering) {
  std::string dir = temp_dir();
  std::ofstream(dir + "/plain.hdr") << "precious";
  CliRun r = run("render --mode id -o plain.hdr/out.hdr", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("cannot write plain.hdr/out.hdr"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("rendered"), std::string::npos);
  std::string long_name(300, 'n');
  r = run("render --mode id -o " + long_name + ".hdr", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("cannot write " + long_name), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("rendered"), std::string::npos);
  EXPECT_EQ(read_file(dir + "/plain.hdr"), "precious");
}

TEST(Cli, WritesEveryRequestedFormat) {
  std::string dir = temp_dir();
  CliRun r = run("render " + source_path("scenes/sphere.scn") +
                     " --mode normal -o a.hdr -o a.png -o a.pfm --quiet",
                 dir);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "a.hdr\na.png\na.pfm\n");
  EXPECT_EQ(read_file(dir + "/a.png").substr(1, 3), "PNG");
  EXPECT_EQ(read_file(dir + "/a.pfm").substr(0, 3), "PF\n");
  for (const auto& e : fs::directory_iterator(dir))  // no temporary files left behind
    EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
}

TEST(Cli, InfoDescribesTheModel) {
  std::string dir = temp_dir();
  CliRun r = run("info " + source_path("scenes/testscene.scn"), dir);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("triangles"), std::string::npos);
  EXPECT_NE(r.out.find("lights: 1 emitting primitives"), std::string::npos);
  EXPECT_NE(r.out.find("screen: 400 x 300"), std::string::npos);
}

}  // namespace
}  // namespace raylane
