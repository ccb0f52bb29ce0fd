// `raylane render --stats-json FILE` (README.md, "Using it"): the summary and the phases as one
// JSON object, with the numbers the render's own counts give, checked before any work like every
// output.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;
using testing::dir_with_scene;
using testing::read_file;
using testing::run_cli;

const char* kScene =
    "screen 8 6\ncamera 0 0 5 1\nlight 2 2 2\nsphere 0 3 3 1\n"
    "brdf 0.5 0.5 0.5 0 0 0 1\nsphere 0 0 0 1\n";

// The whole number after "key": in the JSON text; -1 if none.
long long number_of(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": ([0-9]+)[,}]"))) return -1;
  return std::stoll(m[1]);
}

TEST(CliStatsJson, APathRenderWritesItsSummaryAndPhasesAsOneObject) {
  std::string dir = dir_with_scene(kScene);
  auto r = run_cli("render s.scn --spp 3 --threads 1 --stats-json s.json -o a.hdr", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  std::string json = read_file(dir + "/s.json");
  ASSERT_FALSE(json.empty());
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.substr(json.size() - 2), "}\n");
  for (const char* part :
       {"{\"width\": 8, \"height\": 6, \"mode\": \"path\", \"integrator\": \"mis\", "
        "\"sampler\": \"sobol\", \"shading\": \"float\", \"spp\": 3, \"interrupted\": false, ",
        "\"phases\": {\"camera_rays\": ", "\"idle_and_other\": ", "\"tracer\": \"packet\"",
        "\"threads\": 1, \"processes\": 1, ", "\"outputs\": [\"a.hdr\"]}"})
    EXPECT_NE(json.find(part), std::string::npos) << part << "\n" << json;
  // One camera ray per pixel and pass; the total is the kinds' sum and the summary line's.
  EXPECT_EQ(number_of(json, "camera"), 8 * 6 * 3) << json;
  long long total = number_of(json, "total");
  EXPECT_EQ(total,
            number_of(json, "camera") + number_of(json, "bounce") + number_of(json, "shadow"));
  EXPECT_NE(r.out.find(": " + std::to_string(total) + " rays, "), std::string::npos) << r.out;
  EXPECT_GT(number_of(json, "bounce"), 0) << json;
  // --stats-json alone prints no phases table (that is --stats).
  EXPECT_EQ(r.out.find("where the time went"), std::string::npos) << r.out;
}

TEST(CliStatsJson, ARayCastViewHasNoPhasesAndNoIntegrator) {
  std::string dir = dir_with_scene(kScene);
  auto r = run_cli("render s.scn --mode normal --stats-json s.json -o a.pfm -q", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  std::string json = read_file(dir + "/s.json");
  EXPECT_NE(json.find("\"mode\": \"normal\", \"spp\": 1, "), std::string::npos) << json;
  EXPECT_NE(json.find("\"phases\": null"), std::string::npos) << json;
  EXPECT_EQ(json.find("integrator"), std::string::npos) << json;
  EXPECT_EQ(number_of(json, "camera"), 8 * 6) << json;
}

// Checked before any work, like the images: never over an input, never into a missing folder.
// File names are bytes; JSON is UTF-8. Bytes that are no UTF-8 become U+FFFD, well-formed
// names (an accent, a CJK character) stay as they are, and the file is valid UTF-8 by iconv's
// reading (glibc's decoder, independent of ours).
TEST(CliStatsJson, OutputNamesThatAreNotUtf8KeepTheFileJson) {
  std::string dir = dir_with_scene(kScene);
  auto r = run_cli(
      "render s.scn --mode normal -q --stats-json s.json -o '\xff\xc0\x80.pfm' "
      "-o '\xed\xa0\x80x.pfm' -o 'caf\xc3\xa9\xe6\x97\xa5.pfm'",
      dir);
  ASSERT_EQ(r.status, 0) << r.out;
  std::string json = read_file(dir + "/s.json");
  EXPECT_NE(json.find("\"\\ufffd\\ufffd\\ufffd.pfm\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"\\ufffd\\ufffd\\ufffdx.pfm\""), std::string::npos) << json;  // a surrogate
  EXPECT_NE(json.find("\"caf\xc3\xa9\xe6\x97\xa5.pfm\""), std::string::npos) << json;
  auto valid = run_cli("--version && iconv -f UTF-8 -t UTF-8 s.json > /dev/null", dir);
  EXPECT_EQ(valid.status, 0) << valid.out;
}

TEST(CliStatsJson, AFileThatCannotBeWrittenIsAUsageErrorBeforeAnyWork) {
  std::string dir = dir_with_scene(kScene);
  std::string scene = read_file(dir + "/s.scn");
  auto input = run_cli("render s.scn --spp 1 --stats-json s.scn -o a.hdr", dir);
  EXPECT_EQ(input.status, 2) << input.out;
  EXPECT_EQ(read_file(dir + "/s.scn"), scene);
  auto missing = run_cli("render s.scn --spp 1 --stats-json no/such/s.json -o b.hdr", dir);
  EXPECT_EQ(missing.status, 2) << missing.out;
  EXPECT_NE(missing.out.find("cannot write no/such/s.json"), std::string::npos) << missing.out;
  EXPECT_FALSE(fs::exists(dir + "/a.hdr"));
  EXPECT_FALSE(fs::exists(dir + "/b.hdr"));
}

}  // namespace
}  // namespace raylane
