// `raylane render --save-at LIST` (the report's pass series): each STEM.N.EXT is the file a
// render stopped at N passes writes, byte for byte, for both samplers, with --png and --aov
// siblings, and when the render resumes a checkpoint; bad lists and clashing names exit 2
// before anything is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::read_file;
using testing::source_path;
using testing::temp_dir;

namespace fs = std::filesystem;

// The exit status of `raylane ARGS`, run in the working directory.
int run_status(const std::string& args) {
  return testing::run_cli(args, ".").status;
}

// Byte for byte, without printing images on a failure.
::testing::AssertionResult same_bytes(const std::string& a, const std::string& b) {
  std::string x = read_file(a), y = read_file(b);
  if (!x.empty() && x == y) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << a << " (" << x.size() << " bytes) and " << b << " (" << y.size() << " bytes) differ";
}

// The glass scene (glossy, transmission, the lanes' general path), small.
std::string scene_args() {
  return source_path("scenes/testscene-glass.scn") + " --set 'screen 40 30' --quiet";
}

// The plain render at --spp n with --png and an albedo AOV, in dir/ref<n>/room.hdr (and its
// siblings): what a saved-at image must equal. Returns the folder.
std::string reference_render(const std::string& common, const std::string& dir, int n) {
  std::string ref = dir + "/ref" + std::to_string(n);
  fs::create_directory(ref);
  EXPECT_EQ(run_status("render " + common + " --spp " + std::to_string(n) +
                       " --png --aov albedo -o " + ref + "/room.hdr"),
            0);
  return ref;
}

TEST(CliSaveAt, EachImageIsTheRenderStoppedAtThatPass) {
  for (std::string sampler : {"sobol", "mt19937"}) {
    SCOPED_TRACE(sampler);
    std::string dir = temp_dir(), common = scene_args() + " --sampler " + sampler;
    ASSERT_EQ(run_status("render " + common + " --spp 5 --save-at 4,1,2 --png --aov albedo -o " +
                         dir + "/room.hdr"),
              0);
    for (int n : {1, 2, 4}) {
      const std::string ref = reference_render(common, dir, n);
      std::string stem = "/room." + std::to_string(n);
      std::string hdr = read_file(dir + stem + ".hdr");
      EXPECT_NE(hdr.find("RAYLANE_SPP=" + std::to_string(n)), std::string::npos) << n;
      EXPECT_TRUE(same_bytes(dir + stem + ".hdr", ref + "/room.hdr"));
      EXPECT_TRUE(same_bytes(dir + stem + ".png", ref + "/room.png"));
      EXPECT_TRUE(same_bytes(dir + stem + ".albedo.pfm", ref + "/room.albedo.pfm"));
    }
    EXPECT_FALSE(fs::exists(dir + "/room.3.hdr"));
    EXPECT_FALSE(fs::exists(dir + "/room.5.hdr"));  // the end of the render is room.hdr
    EXPECT_TRUE(fs::exists(dir + "/room.hdr"));
  }
}

// A resumed film continues the series: a count it already passed is not written (a warning
// says so), the count it holds is written at once, the later ones as the render reaches them.
TEST(CliSaveAt, ResumingWritesTheUninterruptedRendersFiles) {
  std::string dir = temp_dir(), common = scene_args();
  ASSERT_EQ(run_status("render " + common + " --spp 2 --checkpoint " + dir + "/run.film -o " + dir +
                       "/first.hdr"),
            0);
  ASSERT_EQ(run_status("render " + common + " --spp 4 --resume " + dir +
                       "/run.film --save-at 1,2,3 -o " + dir + "/rest.hdr"),
            0);
  EXPECT_FALSE(fs::exists(dir + "/rest.1.hdr"));
  for (int n : {2, 3}) {
    std::string ref = dir + "/ref" + std::to_string(n) + ".hdr";
    ASSERT_EQ(run_status("render " + common + " --spp " + std::to_string(n) + " -o " + ref), 0);
    EXPECT_TRUE(same_bytes(dir + "/rest." + std::to_string(n) + ".hdr", ref));
  }
}

// --stats-json lists the series (for tools/converge): each save's pass count, its cost so far
// (seconds and CPU seconds since the start, growing with the passes: 7 then 8 passes catches
// a per-save interval, which would shrink) and its files, which exist; a render without
// --save-at lists an empty series.
TEST(CliSaveAt, StatsJsonListsEachSavesPassesCostAndFiles) {
  std::string dir = temp_dir(), common = scene_args() + " --threads 1 --spp 8";
  ASSERT_EQ(run_status("render " + common + " --save-at 8,1,7 --png --stats-json " + dir +
                       "/s.json -o " + dir + "/room.hdr"),
            0);
  std::string json = read_file(dir + "/s.json");
  std::regex save(
      "\\{\"spp\": ([0-9]+), \"seconds\": ([-0-9.e]+), \"cpu_seconds\": ([-0-9.e]+), "
      "\"outputs\": \\[\"([^\"]*)\", \"([^\"]*)\"\\]\\}");
  std::vector<int> spp;
  double last_seconds = 0, last_cpu = 0;
  for (std::sregex_iterator it(json.begin(), json.end(), save), end; it != end; ++it) {
    const std::smatch& m = *it;
    int n = std::stoi(m[1]);
    spp.push_back(n);
    double seconds = std::stod(m[2]), cpu = std::stod(m[3]);
    EXPECT_GT(seconds, last_seconds) << json;
    EXPECT_GT(cpu, 0) << json;
    EXPECT_GE(cpu, last_cpu) << json;  // getrusage counts in scheduler ticks
    last_seconds = seconds, last_cpu = cpu;
    EXPECT_EQ(m[4].str(), dir + "/room." + std::to_string(n) + ".hdr");
    EXPECT_EQ(m[5].str(), dir + "/room." + std::to_string(n) + ".png");
    EXPECT_TRUE(fs::exists(m[4].str()) && fs::exists(m[5].str())) << json;
  }
  EXPECT_EQ(spp, (std::vector<int>{1, 7, 8})) << json;
  EXPECT_NE(json.find("]}], \"outputs\": [\"" + dir + "/room.hdr\""), std::string::npos) << json;
  ASSERT_EQ(
      run_status("render " + common + " --stats-json " + dir + "/t.json -o " + dir + "/t.hdr"), 0);
  EXPECT_NE(read_file(dir + "/t.json").find("\"series\": [], \"outputs\": "), std::string::npos);
}

TEST(CliSaveAt, BadListsAndClashingNamesExitTwoAndWriteNothing) {
  std::string dir = temp_dir(), common = scene_args() + " --spp 4 -o " + dir + "/a.hdr";
  for (std::string list : {"0", "-1", "1,,4", "1,", ",1", "x", "2.5", "1;4", "99999999999"})
    EXPECT_EQ(run_status("render " + common + " --save-at '" + list + "'"), 2) << list;
  EXPECT_EQ(run_status("render " + common + " --save-at 2,8"), 2);  // beyond --spp
  // Another output, or another output's series, by the same name.
  EXPECT_EQ(run_status("render " + common + " --save-at 2 -o " + dir + "/a.2.hdr"), 2);
  EXPECT_EQ(run_status("render " + common + " --save-at 2 -o " + dir + "/a.hdr.png"), 0);
  EXPECT_TRUE(fs::remove(dir + "/a.hdr") && fs::remove(dir + "/a.hdr.png"));
  EXPECT_TRUE(fs::remove(dir + "/a.2.hdr") && fs::remove(dir + "/a.hdr.2.png"));
  EXPECT_TRUE(fs::is_empty(dir));
  // --save-at in a ray-casting view does nothing (a warning), and writes no series.
  EXPECT_EQ(run_status("render " + common + " --mode normal --save-at 2"), 0);
  EXPECT_FALSE(fs::exists(dir + "/a.2.hdr"));
}

// -o Image_Pass_{pass}.hdr: the course's names. Every image, the series' and the final one,
// gets its pass count in place of {pass}, with the --png and --aov siblings; each is the file
// --spp N writes. A listed count equal to --spp is one image, written once.
TEST(CliSaveAt, APassPatternNamesEveryImageAsTheCourseDid) {
  std::string dir = temp_dir(), common = scene_args();
  ASSERT_EQ(run_status("render " + common + " --spp 4 --save-at 2,1,4 --png --aov albedo -o '" +
                       dir + "/Image_Pass_{pass}.hdr' --stats-json " + dir + "/s.json"),
            0);
  for (int n : {1, 2, 4}) {
    const std::string ref = reference_render(common, dir, n);
    std::string stem = dir + "/Image_Pass_" + std::to_string(n);
    EXPECT_TRUE(same_bytes(stem + ".hdr", ref + "/room.hdr"));
    EXPECT_TRUE(same_bytes(stem + ".png", ref + "/room.png"));
    EXPECT_TRUE(same_bytes(stem + ".albedo.pfm", ref + "/room.albedo.pfm"));
  }
  for (const auto& f : fs::directory_iterator(dir))
    EXPECT_EQ(f.path().filename().string().find('{'), std::string::npos) << f.path();
  const std::string json = read_file(dir + "/s.json");
  EXPECT_NE(json.find("{\"spp\": 4, "), std::string::npos) << json;
  EXPECT_NE(json.find("Image_Pass_4.hdr"), std::string::npos) << json;
  // Without --save-at the pattern names the final image alone.
  ASSERT_EQ(run_status("render " + common + " --spp 3 -o '" + dir + "/only_{pass}.pfm'"), 0);
  EXPECT_TRUE(fs::exists(dir + "/only_3.pfm"));
}

// Braces that are not {pass}, {pass} in a folder or in a ray-casting view, and a pattern whose
// image is another output's: exit 2 with the reason, nothing written.
TEST(CliSaveAt, BadPassPatternsExitTwoAndWriteNothing) {
  std::string dir = temp_dir(), common = scene_args() + " --spp 2 --save-at 1";
  auto run = [&](const std::string& outputs) {
    return testing::run_cli("render " + common + " " + outputs, dir);
  };
  auto typo = run("-o 'Image_Pass_{pas}.hdr'");
  EXPECT_EQ(typo.status, 2);
  EXPECT_NE(typo.out.find("expected the placeholder {pass} in the output name "
                          "'Image_Pass_{pas}.hdr', found '{pas}'"),
            std::string::npos)
      << typo.out;
  auto open = run("-o 'Image_Pass_{pass.hdr'");
  EXPECT_EQ(open.status, 2);
  EXPECT_NE(open.out.find("found '{'"), std::string::npos) << open.out;
  EXPECT_EQ(run("-o 'a}.hdr'").status, 2);
  auto folder = run("-o 'pass{pass}/a.hdr'");
  EXPECT_EQ(folder.status, 2);
  EXPECT_NE(folder.out.find("found braces in its folder"), std::string::npos) << folder.out;
  auto view = run("--mode normal -o 'n_{pass}.pfm'");
  EXPECT_EQ(view.status, 2);
  EXPECT_NE(view.out.find("--mode normal renders no passes"), std::string::npos) << view.out;
  auto clash = run("-o a.hdr -o 'a.{pass}.hdr'");  // a.1.hdr twice: a's series and the pattern
  EXPECT_EQ(clash.status, 2);
  EXPECT_NE(clash.out.find("'a.1.hdr' are one file"), std::string::npos) << clash.out;
  EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
}  // namespace raylane
