// Messages that say what happened (docs/scene-language.md, "Error classes"): a file of another kind
// given as the scene gets one line naming its kind; `raylane info FILM` shows the film; a rejected
// camera line is one error; usage errors name the command's help; flags that do nothing for the
// outputs warn; counts of one are singular.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>

#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;
using testing::dir_with_scene;
using testing::run_cli;
using testing::source_path;
using testing::temp_dir;
using testing::write_file;

const char* kScene = "screen 8 6\ncamera 0 0 5 1\nbrdf 0.5 0.5 0.5 0 0 0 1\nsphere 0 0 0 1\n";

std::size_t lines_of(const std::string& text) {
  return std::size_t(std::count(text.begin(), text.end(), '\n'));
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(CliMessages, AFileOfAnotherKindGivenAsTheSceneGetsOneLineNamingItsKind) {
  std::string dir = dir_with_scene(kScene);
  ASSERT_EQ(run_cli("render s.scn --spp 1 --checkpoint f.film -o a.hdr -q", dir).status, 0);
  for (const char* out : {"a.png", "a.exr", "a.pfm"})
    ASSERT_EQ(run_cli(std::string("render s.scn --mode normal -q -o ") + out, dir).status, 0);
  fs::copy_file(source_path("scenes/letterX.ply"), dir + "/x.ply");
  write_file(dir + "/photo.jpg", std::string("\xff\xd8\xff\xe0\x00\x10JFIF\x00", 11));
  write_file(dir + "/room.pbrt",
             "LookAt 0 5 0  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" 45\nWorldBegin\n"
             "Shape \"sphere\" \"float radius\" 1\n");
  write_file(dir + "/room.xml",
             "<scene version=\"3.0.0\">\n  <shape type=\"sphere\"/>\n</scene>\n");
  write_file(dir + "/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  std::string noise(4096, '\0');
  std::mt19937 rng(1);
  for (char& c : noise)
    c = char(rng() & 0xff);
  write_file(dir + "/noise.scn", noise);
  fs::create_directory(dir + "/scenes");
  write_file(dir + "/scenes/b.scn", kScene);
  write_file(dir + "/scenes/a.scn", kScene);
  const std::pair<std::string, std::string> cases[] = {
      {"f.film",
       "f.film: a raylane film, not a scene: continue it with `raylane render SCENE --resume "
       "f.film`; `raylane info f.film` shows what it holds"},
      {"x.ply", "x.ply: a PLY mesh, not a scene: a scene places a mesh with `mesh FILE"},
      {"a.png", "a.png: a PNG image, not a scene: a scene reads images with `texture FILE`"},
      {"photo.jpg", "photo.jpg: a JPEG image, not a scene"},
      {"a.hdr", "a.hdr: a Radiance HDR image, not a scene"},
      {"a.exr", "a.exr: an OpenEXR image, not a scene"},
      {"a.pfm", "a.pfm: a PFM image, not a scene"},
      {"room.pbrt", "room.pbrt: a pbrt scene, not a scene: raylane reads the CS500 scene language"},
      {"room.xml", "room.xml: a Mitsuba scene, not a scene"},
      {"tri.obj", "tri.obj: a Wavefront OBJ mesh, not a scene"},
      {"noise.scn", "noise.scn: binary data, not a scene: a scene is text"},
      {"scenes", "scenes: a directory, not a scene file: name a .scn file (it holds a.scn, b.scn)"},
  };
  for (const auto& [file, expected] : cases) {
    // `info` reads films and meshes (by their names: .ply, .obj, .xml), so only the others.
    bool info_too = file != "f.film" && file != "x.ply" && file != "tri.obj" && file != "room.xml";
    for (std::string command : {"render ", "info "}) {
      if (command == "info " && !info_too) continue;
      auto r = run_cli(command + file, dir);
      EXPECT_EQ(r.status, 2) << command << file << "\n" << r.out;
      EXPECT_TRUE(has(r.out, expected)) << command << file << "\n" << r.out;
      EXPECT_EQ(lines_of(r.out), 1u) << command << file << "\n" << r.out;
    }
  }
}

// The rule for binary data must not swallow a scene's own errors: a text scene with a stray
// NUL byte still gets the line and column of it.
TEST(CliMessages, ATextSceneWithAStrayControlByteKeepsItsLineErrors) {
  std::string dir = dir_with_scene(std::string(kScene) + std::string("sphere 1 1 1 1\0\n", 16));
  auto r = run_cli("render s.scn --spp 1", dir);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_TRUE(has(r.out, "s.scn:5:")) << r.out;
  EXPECT_FALSE(has(r.out, "binary data")) << r.out;
}

TEST(CliMessages, InfoOnAFilmShowsItsSizeSppSeedIntegratorAndAovs) {
  std::string dir = dir_with_scene(kScene);
  ASSERT_EQ(run_cli("render s.scn --spp 3 --seed 5 --integrator nee --sampler mt19937 "
                    "--aov albedo,depth --checkpoint f.film -o a.exr -q",
                    dir)
                .status,
            0);
  auto r = run_cli("info f.film", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* line : {"film: 'f.film'\n", "size: 8 x 6\n", "spp: 3\n", "seed: 5\n",
                           "integrator: nee\n", "sampler: mt19937\n", "aovs: albedo,depth\n"})
    EXPECT_TRUE(has(r.out, line)) << line << "\n" << r.out;
  write_file(dir + "/cut.film", "RLFILM2");  // a magic and nothing after it
  auto cut = run_cli("info cut.film", dir);
  EXPECT_EQ(cut.status, 2) << cut.out;
}

TEST(CliMessages, ARejectedCameraLineIsOneErrorWithTheSpacedHint) {
  std::string dir = dir_with_scene("screen 8 6\ncamera 0 -6 0 0.5 x90\nsphere 0 0 0 1\n");
  auto r = run_cli("render s.scn --spp 1 -q", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out,
            "s.scn:2:19: expected a rotation (x, y, z, a or q), found 'x90' (write 'x 90': the "
            "letter and its numbers are separate tokens)\n"
            "raylane: 1 error in the scene; nothing rendered\n");
}

TEST(CliMessages, UsageErrorsNameTheCommandsOwnHelp) {
  std::string dir = temp_dir();
  const std::pair<const char*, const char*> cases[] = {
      {"render --bogus", "(see raylane render --help)"},
      {"render --spp x", "(see raylane render --help)"},
      {"info a.scn b.scn", "(see raylane info --help)"},
      {"convert a.hdr", "(see raylane convert --help)"},
      {"diff a.hdr", "(see raylane diff --help)"},
      {"trace", "(see raylane trace --help)"},
      {"frobnicate", "(see raylane --help)"},
  };
  for (const auto& [args, hint] : cases) {
    auto r = run_cli(args, dir);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
    EXPECT_TRUE(has(r.out, hint)) << args << "\n" << r.out;
  }
}

TEST(CliMessages, FlagsThatDoNothingForTheChosenOutputsWarn) {
  std::string dir = dir_with_scene(kScene);
  auto hdr = run_cli("render s.scn --spp 1 -o a.hdr --exposure 2 --half", dir);
  ASSERT_EQ(hdr.status, 0) << hdr.out;
  EXPECT_TRUE(has(hdr.out, "warning: --exposure does nothing without a .png output")) << hdr.out;
  EXPECT_TRUE(has(hdr.out, "warning: --half does nothing without an .exr output")) << hdr.out;
  for (const char* used : {"-o b.png --exposure 2", "-o b.hdr --png --exposure 2"}) {
    auto png = run_cli(std::string("render s.scn --spp 1 ") + used, dir);
    ASSERT_EQ(png.status, 0) << png.out;
    EXPECT_FALSE(has(png.out, "--exposure does nothing")) << used << "\n" << png.out;
  }
  auto convert = run_cli("convert a.hdr c.pfm --exposure 1", dir);
  ASSERT_EQ(convert.status, 0) << convert.out;
  EXPECT_TRUE(has(convert.out, "warning: --exposure does nothing unless OUT is a .png"))
      << convert.out;
}

TEST(CliMessages, CountsOfOneAreSingular) {
  std::string dir = dir_with_scene(kScene);
  auto r = run_cli("render s.scn --spp 1 --threads 1 --stats -o a.hdr", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, ", 1 thread; BVH of 1 node built")) << r.out;
  EXPECT_TRUE(has(r.out, "thread-seconds of 1 thread ×")) << r.out;
  EXPECT_FALSE(has(r.out, " 1 threads")) << r.out;
  auto two = run_cli("render s.scn --spp 1 --threads 2 -o b.hdr", dir);
  EXPECT_TRUE(has(two.out, ", 2 threads; BVH")) << two.out;
}

}  // namespace
}  // namespace raylane
