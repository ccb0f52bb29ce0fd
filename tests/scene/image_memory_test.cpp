// A scene's image memory (docs/scene-language.md, "Image memory"): 4k textures and 8k or 16k
// skies load by default, what each image needs is counted from its header, a refusal names the
// --image-memory figure that reads every image, and decompression bombs are refused by the
// ratio rule unless the user chooses the image memory.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <string>

#include "raylane/core/memory.h"
#include "raylane/scene/parser.h"
#include "scene/scene_test_util.h"
#include "support/hostile_files.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::errors;
using ::testing::HasSubstr;
using testing::kCameraLine;
using testing::temp_dir;

constexpr uint64_t kMiB = uint64_t(1) << 20;

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

ParsedScene load(const std::string& dir, const std::string& scene, const ParseOptions& options) {
  write_file(dir + "/s.scn", std::string(kCameraLine) + "brdf 0.5 0.5 0.5 0 0 0 1\n" + scene);
  return load_scene_file(dir + "/s.scn", options);
}

std::string all_errors(const ParsedScene& p) {
  std::string all;
  for (const std::string& e : errors(p))
    all += e + "\n";
  return all;
}

// A 4096² texture (black: a 13 KB PNG) and an 8192×4096 sky, the assets of the report.
std::string assets_dir() {
  std::string dir = temp_dir();
  write_file(dir + "/t4k.png", testing::png_zero_bomb(4096, 4096));
  write_file(dir + "/sky8k.hdr", testing::flat_hdr(8192, 4096));
  return dir;
}
const char* kAssets = "texture t4k.png\nenvironment sky8k.hdr 1\n";

TEST(SceneImageMemory, A4kTextureAndAn8kSkyKeepTheirFilesBytes) {
  std::string dir = assets_dir();
  ParseOptions options;
  options.image_memory = 1024 * kMiB;  // what they need, 352 MiB, and to spare
  auto p = load(dir, kAssets, options);
  ASSERT_TRUE(p.ok()) << all_errors(p);
  ASSERT_EQ(p.scene.textures.size(), 1u);
  EXPECT_EQ(p.scene.textures[0].texels.format, TexelFormat::kSrgb8);
  EXPECT_EQ(p.scene.textures[0].texels.bytes(), 64 * kMiB);
  ASSERT_TRUE(p.scene.environment);
  EXPECT_EQ(p.scene.environment->texels->format, TexelFormat::kRgbe);
  EXPECT_EQ(p.scene.environment->texels->bytes(), 128 * kMiB);
  EXPECT_EQ(p.scene.environment->texels->at(8191, 4095), glm::vec3(1, 1, 1));
  ASSERT_EQ(p.images.images.size(), 2u);
  EXPECT_EQ(p.images.images[0].kept, 64 * kMiB);
  // The texels and 5 bytes a pixel of tables (a fixed-point CDF entry, a quarter of a guide
  // entry).
  EXPECT_EQ(p.images.images[1].kept, 288 * kMiB);
  EXPECT_EQ(p.images.wanted, 352 * kMiB);
}

// Headers only, as `raylane info` reads them: a 16384×8192 sky takes 1.1 GiB, which the default
// of a 24 GiB desktop with 20 GiB available (10 GiB) holds.
TEST(SceneImageMemory, A16kSkyFitsTheDefaultOfA24GiBDesktop) {
  std::string dir = temp_dir();
  write_file(dir + "/sky16k.hdr", testing::flat_hdr(16384, 8192));
  ParseOptions options;
  options.image_headers_only = true;
  options.image_memory = default_image_memory_of(uint64_t(20) << 30);
  auto p = load(dir, "environment sky16k.hdr 1\n", options);
  ASSERT_TRUE(p.ok()) << all_errors(p);
  ASSERT_EQ(p.images.images.size(), 1u);
  EXPECT_EQ(p.images.images[0].kept, 1152 * kMiB);
  EXPECT_EQ(p.images.images[0].refused, "");
}

// The figure a refusal gives reads every image of the scene, the ones after it too: one retry
// with it loads the scene, and one MiB less does not.
TEST(SceneImageMemory, ARefusalGivesTheFigureThatReadsEveryImage) {
  std::string dir = assets_dir();
  write_file(dir + "/b.png", testing::png_zero_bomb(1024, 1024));
  std::string scene = std::string(kAssets) + "brdf 1 1 1 0 0 0 1\ntexture b.png\n";
  ParseOptions options;
  options.image_memory = 300 * kMiB;
  options.image_memory_chosen = true;
  auto p = load(dir, scene, options);
  ASSERT_FALSE(p.ok());
  std::string all = all_errors(p);
  EXPECT_THAT(all, HasSubstr("s.scn:4:13: cannot use environment 'sky8k.hdr': "));
  std::smatch m;
  ASSERT_TRUE(std::regex_search(all, m, std::regex("--image-memory ([0-9]+) reads them"))) << all;
  uint64_t mib = std::stoull(m[1]);
  // The 1024² texture peaks at 11 MiB and its file's 1 KB beside the 352 MiB kept.
  EXPECT_EQ(mib, 64 + 288 + 11 + 1);
  options.image_memory = (mib - 1) * kMiB;
  EXPECT_FALSE(load(dir, scene, options).ok());
  options.image_memory = mib * kMiB;
  auto retry = load(dir, scene, options);
  EXPECT_TRUE(retry.ok()) << all_errors(retry);
}

// An 8192² PNG bomb of 53 KB decodes to 704 MiB of samples and texels: refused at the default
// image memory however large it is, read when the user chooses the image memory.
TEST(SceneImageMemory, ABombIsRefusedByTheRatioRuleUnlessTheUserChoosesTheMemory) {
  std::string dir = temp_dir();
  write_file(dir + "/bomb.png", testing::png_zero_bomb(8192, 8192));
  ParseOptions options;
  options.image_memory = uint64_t(64) << 30;
  auto p = load(dir, "texture bomb.png\n", options);
  EXPECT_THAT(all_errors(p),
              HasSubstr("s.scn:3:9: cannot use texture 'bomb.png': " + dir +
                        "/bomb.png: "
                        "reading its 8192x8192 pixels takes 704.1 MiB from a file of "))
      << all_errors(p);
  EXPECT_THAT(all_errors(p), HasSubstr(" bytes, more than 1024 times its size")) << all_errors(p);
  options.image_memory_chosen = true;
  options.image_headers_only = true;  // decoding it would only show the same
  auto chosen = load(dir, "texture bomb.png\n", options);
  EXPECT_TRUE(chosen.ok()) << all_errors(chosen);
  EXPECT_EQ(chosen.images.images.at(0).refused, "");
}

// A mesh file's texture that is refused is dropped, not fatal; the mesh's warning says how many
// of its textures were dropped and why.
TEST(SceneImageMemory, AMeshSaysHowManyOfItsTexturesWereDropped) {
  std::string dir = temp_dir();
  write_file(dir + "/ok.png", testing::png_zero_bomb(8, 8));
  write_file(dir + "/m.mtl",
             "newmtl a\nKd 1 1 1\nmap_Kd ok.png\nnewmtl b\nKd 1 1 1\nmap_Kd gone.png\n");
  write_file(dir + "/m.obj",
             "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n"
             "usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 2/2 4/4 3/3\n");
  auto p = load(dir, "mesh m.obj 0 0 0 1\n", ParseOptions{});
  ASSERT_TRUE(p.ok()) << all_errors(p);
  auto w = testing::warnings(p);
  std::string all;
  for (const std::string& s : w)
    all += s + "\n";
  EXPECT_THAT(all, HasSubstr("mesh 'm.obj': 1 of its 2 textures cannot be used, so the "
                             "triangles whose materials name it render untextured"))
      << all;
  EXPECT_THAT(all, HasSubstr("gone.png"));
  EXPECT_THAT(all, ::testing::Not(HasSubstr("the mesh renders untextured"))) << all;
  EXPECT_EQ(p.scene.textures.size(), 1u);
}

}  // namespace
}  // namespace raylane
