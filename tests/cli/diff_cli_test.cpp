// `raylane diff`: the numbers of two images and the exit status scripts rely on.
#include <gtest/gtest.h>

#include <cmath>

#include "raylane/image/write_image.h"
#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::run_cli;
using testing::temp_dir;

TEST(CliDiff, ReportsTheDifferenceAndExitsByTolerance) {
  std::string dir = temp_dir();
  Image a(4, 2), b(4, 2), small(2, 2);
  b.set(1, 1, Vec3f(0.6f, 0, 0));  // one channel of 24 differs by 0.6: RMSE = sqrt(0.36 / 24)
  ASSERT_TRUE(write_image(dir + "/a.pfm", a).ok());
  ASSERT_TRUE(write_image(dir + "/b.pfm", b).ok());
  ASSERT_TRUE(write_image(dir + "/small.pfm", small).ok());

  auto same = run_cli("diff a.pfm a.pfm", dir);
  EXPECT_EQ(same.status, 0) << same.out;
  EXPECT_NE(same.out.find("rmse 0 "), std::string::npos) << same.out;

  auto differ = run_cli("diff b.pfm a.pfm", dir);
  EXPECT_EQ(differ.status, 1) << differ.out;
  EXPECT_NE(differ.out.find("rmse 0.122474 "), std::string::npos) << differ.out;
  EXPECT_NE(differ.out.find("max_abs 0.6"), std::string::npos) << differ.out;
  EXPECT_EQ(run_cli("diff b.pfm a.pfm --tol 0.2", dir).status, 0);

  EXPECT_EQ(run_cli("diff small.pfm a.pfm", dir).status, 2);
  EXPECT_EQ(run_cli("diff missing.pfm a.pfm", dir).status, 2);
  EXPECT_EQ(run_cli("diff a.pfm", dir).status, 2);
  EXPECT_EQ(run_cli("diff a.pfm a.pfm --tol -1", dir).status, 2);
  auto sizes = run_cli("diff small.pfm a.pfm", dir);
  EXPECT_NE(sizes.out.find("small.pfm is 2x2 and a.pfm is 4x2"), std::string::npos) << sizes.out;
}

// A NaN or infinite pixel is a difference no tolerance forgives, and the output says so.
TEST(CliDiff, NonFinitePixelsDifferBeyondAnyTolerance) {
  std::string dir = temp_dir();
  Image a(2, 2), nan(2, 2);
  nan.set(1, 0, Vec3f(std::nanf(""), 0, 0));
  ASSERT_TRUE(write_image(dir + "/a.pfm", a).ok());
  ASSERT_TRUE(write_image(dir + "/nan.pfm", nan).ok());
  for (std::string args :
       {"diff nan.pfm a.pfm --tol 1e30", "diff a.pfm nan.pfm --tol 1e30", "diff nan.pfm nan.pfm"}) {
    auto r = run_cli(args, dir);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.out;
    EXPECT_NE(r.out.find("1 channel values are NaN or infinite"), std::string::npos) << r.out;
  }
}

}  // namespace
}  // namespace raylane
