// Every command that reads images takes --image-memory with the same rules (docs/scene-language.md,
// "Image memory"): `diff` compares the headers' sizes before decoding, `convert` and `diff`
// check the memory from the headers and name the figure that reads the images, `info` lists
// the environment and each texture with its memory and exits 2 when render would refuse one.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <string>

#include "raylane/core/alloc_budget.h"
#include "support/cli_run.h"
#include "support/hostile_files.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::run_cli;
using testing::run_cli_within;
using testing::temp_dir;

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// The figure N of "--image-memory N reads ..." in a message, or 0.
uint64_t figure(const std::string& out) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex("--image-memory ([0-9]+) reads"))) return 0;
  return std::stoull(m[1]);
}

// An 8192² sky beside a 16² one: decoding the first as floats takes 1 GiB, more than the
// 256 MiB of address space the command has; their headers tell the sizes apart.
TEST(CliImageMemory, DiffComparesTheSizesBeforeDecoding) {
  if (!AllocBudget::enforced()) GTEST_SKIP() << "sanitizer build: ulimit -v cannot hold it";
  std::string dir = temp_dir();
  write_file(dir + "/big.hdr", testing::flat_hdr(8192, 8192));
  write_file(dir + "/small.hdr", testing::flat_hdr(16, 16));
  auto r = run_cli_within("diff big.hdr small.hdr", dir, 256 << 10);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("big.hdr is 8192x8192 and small.hdr is 16x16: images of different sizes"),
            std::string::npos)
      << r.out;
}

TEST(CliImageMemory, ConvertAndDiffNameTheFigureThatReadsTheImages) {
  std::string dir = temp_dir();
  write_file(dir + "/a.hdr", testing::flat_hdr(1024, 512));
  auto diff = run_cli("diff a.hdr a.hdr --image-memory 8", dir);
  EXPECT_EQ(diff.status, 2) << diff.out;
  uint64_t n = figure(diff.out);
  // The first kept as 6 MiB of floats while the second decodes (8 MiB and its 38 KB file).
  EXPECT_EQ(n, 15u) << diff.out;
  EXPECT_EQ(run_cli("diff a.hdr a.hdr --image-memory " + std::to_string(n - 1), dir).status, 2);
  auto again = run_cli("diff a.hdr a.hdr --image-memory " + std::to_string(n), dir);
  EXPECT_EQ(again.status, 0) << again.out;
  auto convert = run_cli("convert a.hdr a.pfm --image-memory 4", dir);
  EXPECT_EQ(convert.status, 2) << convert.out;
  n = figure(convert.out);
  ASSERT_GT(n, 4u) << convert.out;
  auto retry = run_cli("convert a.hdr a.pfm --image-memory " + std::to_string(n), dir);
  EXPECT_EQ(retry.status, 0) << retry.out;
}

// A PNG bomb converts only when the user chooses the image memory.
TEST(CliImageMemory, ConvertRefusesABombAtTheDefault) {
  std::string dir = temp_dir();
  write_file(dir + "/bomb.png", testing::png_zero_bomb(8192, 8192));
  auto r = run_cli("convert bomb.png out.hdr", dir);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("more than 1024 times its size"), std::string::npos) << r.out;
  EXPECT_GT(figure(r.out), 1024u) << r.out;
}

// info lists the environment and the texture with their memory; at an image memory that cannot
// hold them it warns for each, exits 2 and names the figure with which render then renders.
TEST(CliImageMemory, InfoListsEveryImageAndTheFigureRenderNeeds) {
  std::string dir = temp_dir();
  write_file(dir + "/sky.hdr", testing::flat_hdr(2048, 1024));
  write_file(dir + "/t.png", testing::png_zero_bomb(1024, 1024));
  write_file(dir + "/s.scn",
             "screen 8 6\ncamera 0 0 5 1\nbrdf 0.5 0.5 0.5 0 0 0 1\ntexture t.png\n"
             "sphere 0 0 0 1\nenvironment sky.hdr 1\n");
  auto fits = run_cli("info s.scn --image-memory 100", dir);
  EXPECT_EQ(fits.status, 0) << fits.out;
  EXPECT_NE(fits.out.find("texture      1024 x 1024, keeps 4.0 MiB, reading peaks at 11.0 MiB: "
                          "'t.png'"),
            std::string::npos)
      << fits.out;
  EXPECT_NE(fits.out.find("environment  2048 x 1024, keeps 18.0 MiB, reading peaks at 18.0 MiB: "
                          "'sky.hdr'"),
            std::string::npos)
      << fits.out;
  auto tight = run_cli("info s.scn --image-memory 15", dir);
  EXPECT_EQ(tight.status, 2) << tight.out;
  EXPECT_NE(tight.out.find("warning: render refuses it: reading its 2048x1024 pixels takes "
                           "18.0 MiB; the image memory left is 11.0 MiB"),
            std::string::npos)
      << tight.out;
  uint64_t n = figure(tight.out);
  EXPECT_EQ(n, 22u) << tight.out;
  auto refused = run_cli("render s.scn --spp 1 -o a.hdr --image-memory 15", dir);
  EXPECT_EQ(refused.status, 2) << refused.out;
  EXPECT_EQ(figure(refused.out), n) << refused.out;
  auto render = run_cli("render s.scn --spp 1 -o a.hdr --image-memory " + std::to_string(n), dir);
  EXPECT_EQ(render.status, 0) << render.out;
}

}  // namespace
}  // namespace raylane
