// CSG blocks through the `raylane` program (docs/scene-language.md, "CSG blocks"): `info` lists
// each block; a bad block stops a render with status 2 and its message, and --lenient skips it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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

}  // namespace
}  // namespace raylane
