// CSG blocks through the `raylane` program (docs/scene-language.md, "CSG blocks"): `info` lists
// each block; a bad block stops a render with status 2 and its message, and --lenient skips it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::run_cli;
using testing::source_path;
using testing::temp_dir;

TEST(CsgCli, InfoListsEachBlock) {
  testing::CliRun r = run_cli("info " + source_path("scenes/csg.scn"), temp_dir());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("csg blocks          3 rows"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("csg block 0: 2 leaves (sphere sphere), program 0 1 intersect, bounds "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("csg block 1: 3 leaves (box cylinder cylinder), program 0 1 difference 2 "
                       "difference, bounds (1.4 -0.5 -1) to (3 1.1 0.6)"),
            std::string::npos)
      << r.out;
}

TEST(CsgCli, ABadBlockStopsTheRenderAndLenientSkipsIt) {
  std::string dir = temp_dir();
  std::ofstream(dir + "/bad.scn") << "screen 8 8\ncamera 0 0 5 0.5\nbrdf 0.5 0.5 0.5 0 0 0 10\n"
                                     "csg\nsphere 0 0 0 1\nunion\nend\nsphere 3 0 0 1\n";
  testing::CliRun r = run_cli("render bad.scn --mode normal -o bad.png", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("bad.scn:6:1: union pops two solids: expected at least 2 on the csg "
                       "block's stack, found 1"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/bad.png"));
  r = run_cli("render bad.scn --mode normal --lenient -o bad.png", dir);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("skipped the csg block opened at line 4 whole"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir + "/bad.png"));
}

// The path tracer on the glass lens, the drilled box and the bitten sphere: every pixel finite.
TEST(CsgCli, ThePathTracedExamplesAreFinite) {
  std::string dir = temp_dir();
  testing::CliRun r = run_cli(
      "render " + source_path("scenes/csg.scn") + " --spp 8 --set 'screen 64 48' -o csg.pfm", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream in(dir + "/csg.pfm", std::ios::binary);
  std::string magic, scale;
  int w = 0, h = 0;
  in >> magic >> w >> h >> scale;
  in.get();  // the newline after the scale
  ASSERT_EQ(magic, "PF");
  ASSERT_EQ(w * h, 64 * 48);
  std::vector<float> rgb(std::size_t(w) * h * 3);
  in.read(reinterpret_cast<char*>(rgb.data()), std::streamsize(rgb.size() * sizeof(float)));
  ASSERT_TRUE(in.good());
  int lit = 0;
  for (float v : rgb) {
    ASSERT_TRUE(std::isfinite(v));
    lit += v > 0;
  }
  EXPECT_GT(lit, int(rgb.size()) / 4);
}

}  // namespace
}  // namespace raylane
