// `raylane render --region X0,Y0,X1,Y1` (render/film/region.h): the files hold the rectangle, bit for
// bit the whole render's pixels (colour, AOV layers, ray-casting views); a checkpoint records
// the region and resumes only with it; bad values are usage errors that write nothing.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "raylane/image/exr.h"
#include "raylane/image/write_image.h"
#include "raylane/render/film/region.h"
#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::run_cli;

// The course scene at 72x52 (tiles cut at the right and bottom edges).
std::string course(const std::string& more) {
  return "render " + testing::source_path("scenes/testscene.scn") + " --set 'screen 72 52' -q " +
         more;
}

const PixelRegion kRegion{10, 3, 40, 30};

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

Image read(const std::string& path) {
  auto image = read_image(path);
  EXPECT_TRUE(image.ok()) << image.error();
  return image.ok() ? *image : Image();
}

TEST(CliRegion, FilesHoldTheRectangleOfTheWholeRenderBitForBit) {
  std::string dir = testing::temp_dir();
  for (const char* sampler : {"mt19937", "sobol"}) {
    SCOPED_TRACE(sampler);
    const std::string run = std::string("--spp 2 --aov depth --sampler ") + sampler;
    auto whole = run_cli(course(run + " -o whole.pfm -o whole.exr"), dir);
    ASSERT_EQ(whole.status, 0) << whole.out;
    auto part = run_cli(
        course(run + " --region 10,3,40,30 -o part.pfm -o part.exr --stats-json part.json"), dir);
    ASSERT_EQ(part.status, 0) << part.out;
    Image cut = read(dir + "/part.pfm");
    EXPECT_EQ(cut.width, 30u);
    EXPECT_EQ(cut.height, 27u);
    EXPECT_TRUE(same_bits(cut.rgb, crop(read(dir + "/whole.pfm"), kRegion).rgb));
    const std::string exr = testing::read_file(dir + "/part.exr");
    auto depth = decode_exr_layer(exr, "depth");
    auto whole_depth = decode_exr_layer(testing::read_file(dir + "/whole.exr"), "depth");
    ASSERT_TRUE(depth.ok() && whole_depth.ok());
    EXPECT_TRUE(same_bits(depth->data, crop(whole_depth->data, 72, 1, kRegion)));
    auto info = probe_exr(exr);
    ASSERT_TRUE(info.ok());
    EXPECT_NE(std::find(info->metadata.begin(), info->metadata.end(), "RAYLANE_REGION=10,3,40,30"),
              info->metadata.end());
    EXPECT_NE(testing::read_file(dir + "/part.json").find("\"region\": [10, 3, 40, 30]"),
              std::string::npos);
  }
  for (const char* mode : {"depth", "lit"}) {
    SCOPED_TRACE(mode);
    ASSERT_EQ(run_cli(course(std::string("--mode ") + mode + " -o view.pfm"), dir).status, 0);
    auto part =
        run_cli(course(std::string("--mode ") + mode + " --region 10,3,40,30 -o v.pfm"), dir);
    ASSERT_EQ(part.status, 0) << part.out;
    EXPECT_TRUE(same_bits(read(dir + "/v.pfm").rgb, crop(read(dir + "/view.pfm"), kRegion).rgb));
  }
}

TEST(CliRegion, ACheckpointRecordsTheRegionAndResumesOnlyWithIt) {
  std::string dir = testing::temp_dir();
  const std::string region = " --region 10,3,40,30";
  ASSERT_EQ(run_cli(course("--spp 2 --checkpoint r.film -o first.pfm" + region), dir).status, 0);
  ASSERT_EQ(run_cli(course("--spp 5 -o plain.pfm" + region), dir).status, 0);
  auto resumed = run_cli(course("--spp 5 --resume r.film -o resumed.pfm" + region), dir);
  ASSERT_EQ(resumed.status, 0) << resumed.out;
  EXPECT_EQ(testing::read_file(dir + "/resumed.pfm"), testing::read_file(dir + "/plain.pfm"));
  auto info = run_cli("info r.film", dir);
  EXPECT_NE(info.out.find("region: 10,3,40,30"), std::string::npos) << info.out;

  auto other = run_cli(course("--spp 5 --resume r.film -o other.pfm --region 0,0,8,8"), dir);
  EXPECT_EQ(other.status, 2) << other.out;
  EXPECT_NE(other.out.find("r.film: the film holds --region 10,3,40,30, this run asks for "
                           "--region 0,0,8,8; resume with --region 10,3,40,30"),
            std::string::npos)
      << other.out;
  auto none = run_cli(course("--spp 5 --resume r.film -o none.pfm"), dir);
  EXPECT_EQ(none.status, 2) << none.out;
  EXPECT_NE(none.out.find("this run asks for the whole image"), std::string::npos) << none.out;
  ASSERT_EQ(run_cli(course("--spp 1 --checkpoint w.film -o w.pfm"), dir).status, 0);
  auto into = run_cli(course("--spp 2 --resume w.film -o into.pfm" + region), dir);
  EXPECT_EQ(into.status, 2) << into.out;
  EXPECT_NE(into.out.find("resume with no --region"), std::string::npos) << into.out;
  for (const char* unwritten : {"other.pfm", "none.pfm", "into.pfm"})
    EXPECT_FALSE(std::filesystem::exists(dir + "/" + unwritten)) << unwritten;
}

TEST(CliRegion, BadValuesAreUsageErrorsThatWriteNothing) {
  std::string dir = testing::temp_dir();
  const std::pair<const char*, const char*> cases[] = {
      {"1,2,3", "it has 3 of the 4"},
      {"1,2,3,4,5", "it has more than 4"},
      {"1,2,3,x", "Y1 is 'x'"},
      {"a,b,c,d", "X0 is 'a'"},
      {"-1,0,5,5", "X0 is '-1'"},
      {"1.5,0,5,5", "X0 is '1.5'"},
      {"0,0,99999999999,5", "(too large)"},
      {"''", "X0 is ''"},
      {"4,2,3,5", "--region 4,2,3,5 is empty"},
      {"0,0,0,0", "is empty"},
      {"0,0,73,10", "--region 0,0,73,10 reaches past the 72x52 image"},
      {"0,40,10,53", "Y1 at most 52"},
  };
  for (const auto& [value, expected] : cases) {
    SCOPED_TRACE(value);
    auto r = run_cli(course(std::string("-o out.pfm --region ") + value), dir);
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find(expected), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("see raylane render --help"), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(dir + "/out.pfm"));
  }
}

}  // namespace
}  // namespace raylane
