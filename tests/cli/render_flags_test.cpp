// What render's flags promise (README.md, "Using it"): --time is a budget, a --resume film that
// holds enough passes and path-only flags in a ray-casting view are said, not silently ignored.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::run_cli;
using testing::temp_dir;

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The spp an HDR file's header records (RAYLANE_SPP=N).
int spp_of(const std::string& hdr) {
  auto at = hdr.find("RAYLANE_SPP=");
  return at == std::string::npos ? -1 : std::stoi(hdr.substr(at + 12));
}

void write_tiny_scene(const std::string& dir) {
  std::ofstream(dir + "/tiny.scn") << "screen 4 4\ncamera 0 0 5 1\nbrdf 0.5 0.5 0.5 0 0 0 1\n"
                                      "sphere 0 0 0 1\nlight 1 1 1\nsphere 0 3 3 1\n";
}

// Without --spp a budget renders until it is spent (a 4x4 image takes far more than 16
// passes in 0.5 s); with both, whichever comes first.
TEST(CliRenderFlags, TimeIsABudgetWithoutSpp) {
  std::string dir = temp_dir();
  write_tiny_scene(dir);
  ASSERT_EQ(run_cli("render tiny.scn --time 0.5 -o t.hdr -q", dir).status, 0);
  EXPECT_GT(spp_of(read_file(dir + "/t.hdr")), 16);
  ASSERT_EQ(run_cli("render tiny.scn --time 60 --spp 3 -o s.hdr -q", dir).status, 0);
  EXPECT_EQ(spp_of(read_file(dir + "/s.hdr")), 3);
}

TEST(CliRenderFlags, ResumingToNoMoreSamplesSaysSo) {
  std::string dir = temp_dir();
  write_tiny_scene(dir);
  ASSERT_EQ(run_cli("render tiny.scn --spp 4 --checkpoint f.film -o a.hdr -q", dir).status, 0);
  auto r = run_cli("render tiny.scn --spp 2 --resume f.film -o b.hdr", dir);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("already holds 4 passes and --spp asks for 2"), std::string::npos) << r.out;
  EXPECT_EQ(spp_of(read_file(dir + "/b.hdr")), 4);
  EXPECT_EQ(read_file(dir + "/a.hdr"), read_file(dir + "/b.hdr"));
}

// A film that does not fit this run says what differs, in the flags' own terms.
TEST(CliRenderFlags, AResumeMismatchNamesWhatDiffers) {
  std::string dir = temp_dir();
  write_tiny_scene(dir);
  ASSERT_EQ(run_cli("render tiny.scn --spp 1 --seed 3 --integrator nee --checkpoint f.film -q", dir)
                .status,
            0);
  auto seed = run_cli("render tiny.scn --spp 2 --resume f.film --integrator nee -o a.hdr", dir);
  EXPECT_EQ(seed.status, 2) << seed.out;
  EXPECT_NE(seed.out.find("rendered with --seed 3 (this run: 0); resume with the same ones"),
            std::string::npos)
      << seed.out;
  auto both =
      run_cli("render tiny.scn --spp 2 --resume f.film --seed 3 --max-depth 5 -o a.hdr", dir);
  EXPECT_NE(both.out.find("--integrator nee (this run: mis); --max-depth 64 (this run: 5)"),
            std::string::npos)
      << both.out;
  auto sampler = run_cli(
      "render tiny.scn --spp 2 --resume f.film --seed 3 --integrator nee --sampler mt19937", dir);
  EXPECT_NE(sampler.out.find("--sampler sobol (this run: mt19937)"), std::string::npos)
      << sampler.out;
  std::ofstream(dir + "/other.scn") << "screen 4 4\ncamera 0 0 6 1\nsphere 0 0 0 1\n";
  auto scene = run_cli("render other.scn --spp 2 --resume f.film --seed 3 --integrator nee", dir);
  EXPECT_NE(scene.out.find("rendered with the scene (its shapes"), std::string::npos) << scene.out;
}

// --stats says where the time went, phase by phase, and changes nothing in the image.
TEST(CliRenderFlags, StatsBreakDownTheRenderAndChangeNothing) {
  std::string dir = temp_dir();
  write_tiny_scene(dir);
  auto r = run_cli("render tiny.scn --spp 8 --stats -o s.hdr", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* row : {"where the time went", "camera rays", "tracing camera rays",
                          "tracing bounce + shadow rays", "shading (BSDF, roulette)",
                          "light sampling", "film", "idle and other", "Mrays/s of tracing time"})
    EXPECT_NE(r.out.find(row), std::string::npos) << row << "\n" << r.out;
  ASSERT_EQ(run_cli("render tiny.scn --spp 8 -o p.hdr -q", dir).status, 0);
  EXPECT_EQ(read_file(dir + "/s.hdr"), read_file(dir + "/p.hdr"));
}

TEST(CliRenderFlags, PathOnlyFlagsInARayCastingViewWarn) {
  std::string dir = temp_dir();
  write_tiny_scene(dir);
  auto r = run_cli("render tiny.scn --mode normal --spp 64 --integrator nee -o n.hdr", dir);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("warning: --spp does nothing in the ray-casting view --mode normal"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("warning: --integrator does nothing"), std::string::npos) << r.out;
  auto quiet = run_cli("render tiny.scn --mode normal --spp 64 -o n.hdr -q", dir);
  EXPECT_EQ(quiet.out.find("warning"), std::string::npos) << quiet.out;
  auto path = run_cli("render tiny.scn --spp 1 -o p.hdr", dir);
  EXPECT_EQ(path.out.find("warning"), std::string::npos) << path.out;
}

// --set changes a render without editing the scene: the override's screen is the image's size
// (the 4x4 scene renders 6x2), and a bad override is an error that names it.
TEST(CliRenderFlags, SetOverridesSceneLines) {
  std::string dir = temp_dir();
  write_tiny_scene(dir);
  auto run = run_cli("render tiny.scn --spp 1 --set 'screen 6 2' -o wide.pfm", dir);
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_NE(run.out.find("--set:1:1: warning: screen given again (first at tiny.scn:1)"),
            std::string::npos)
      << run.out;
  EXPECT_EQ(read_file(dir + "/wide.pfm").substr(0, 8), "PF\n6 2\n-");
  auto bad = run_cli("render tiny.scn --spp 1 --set 'screen 6 0' -o bad.pfm", dir);
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("--set:1:10: screen size must be a whole number >= 1"), std::string::npos)
      << bad.out;
  EXPECT_FALSE(std::ifstream(dir + "/bad.pfm").good());
}

// --aov writes one PFM per AOV beside the outputs (once for outputs that share a stem),
// refuses a bad list, and a --resume film must sum the same AOVs.
TEST(CliRenderFlags, AovsAreSiblingPfmFiles) {
  std::string dir = temp_dir();
  write_tiny_scene(dir);
  auto run = run_cli("render tiny.scn --spp 2 --aov albedo,depth -o a.hdr --png "
                     "--checkpoint a.film -q",
                     dir);
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_EQ(run.out, "a.hdr\na.png\na.albedo.pfm\na.depth.pfm\n");
  EXPECT_EQ(read_file(dir + "/a.depth.pfm").substr(0, 8), "PF\n4 4\n-");
  auto bad = run_cli("render tiny.scn --aov albedo,colour -o b.hdr", dir);
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("--aov: expected a list of albedo, normal, depth, position separated "
                         "by commas, found 'colour'"),
            std::string::npos)
      << bad.out;
  auto other = run_cli("render tiny.scn --spp 3 --aov albedo --resume a.film -o c.hdr", dir);
  EXPECT_EQ(other.status, 2);
  EXPECT_NE(other.out.find("the film sums the AOVs (albedo, depth), this run asks for (albedo)"),
            std::string::npos)
      << other.out;
  EXPECT_FALSE(std::ifstream(dir + "/c.albedo.pfm").good());
}

}  // namespace
}  // namespace raylane
