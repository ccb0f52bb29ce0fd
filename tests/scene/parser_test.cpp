// The scene language, rule by rule (docs/scene-language.md).
#include <gtest/gtest.h>

#include "scene/scene_test_util.h"

namespace raylane {
namespace {

using ::testing::ElementsAre;
using testing::errors;
using testing::kCameraLine;
using testing::parse;
using testing::warnings;

TEST(Parser, ReadsEveryCommand) {
  auto p = parse(
      "screen 640 480\n"
      "camera 1 2 3 0.5 x 90\n"
      "ambient 0.1 0.2 0.3\n"
      "light 5 6 7\n"
      "sphere 1 2 3 0.5\n"
      "brdf 0.1 0.2 0.3 0.4 0.5 0.6 20\n"
      "box 0 0 0 1 2 3\n"
      "brdf 0.1 0.2 0.3 0.4 0.5 0.6 20 0.7 0.8 0.9 1.5\n"
      "cylinder 0 0 0 0 0 2 0.25\n");
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  EXPECT_TRUE(p.diagnostics.items.empty());
  const Scene& s = p.scene;
  EXPECT_EQ(s.width, 640u);
  EXPECT_EQ(s.height, 480u);
  ASSERT_TRUE(s.camera);
  EXPECT_EQ(s.camera->eye, Vec3d(1, 2, 3));
  EXPECT_EQ(s.camera->ry, 0.5);
  EXPECT_EQ(s.ambient, Vec3f(0.1f, 0.2f, 0.3f));
  ASSERT_EQ(s.materials.size(), 3u);
  EXPECT_TRUE(s.materials[0].is_light);
  EXPECT_EQ(s.materials[0].emission, Vec3f(5, 6, 7));
  EXPECT_EQ(s.materials[1].kd, Vec3f(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.materials[1].ks, Vec3f(0.4f, 0.5f, 0.6f));
  EXPECT_EQ(s.materials[1].alpha, 20.0f);
  EXPECT_EQ(s.materials[1].kt, Vec3f(0, 0, 0));
  EXPECT_EQ(s.materials[1].ior, 1.0f);
  EXPECT_EQ(s.materials[2].kt, Vec3f(0.7f, 0.8f, 0.9f));
  EXPECT_EQ(s.materials[2].ior, 1.5f);
  ASSERT_EQ(s.table<Sphere>().size(), 1u);
  EXPECT_EQ(s.table<Sphere>().material[0], 0u);
  ASSERT_EQ(s.table<Box>().size(), 1u);
  EXPECT_EQ(s.table<Box>().hi(0), Vec3f(1, 2, 3));
  EXPECT_EQ(s.table<Box>().material[0], 1u);
  ASSERT_EQ(s.table<Cylinder>().size(), 1u);
  EXPECT_EQ(s.table<Cylinder>().material[0], 2u);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0], PrimRef(tag_of<Sphere>, 0));
  EXPECT_EQ(s.primitive_count(), 3u);
}

TEST(Parser, CommentsBlankLinesTabsAndCrlf) {
  auto p = parse(std::string(kCameraLine) +
                 "# a comment line\n"
                 "\n"
                 "   \t  \n"
                 "sphere\t0 0 0 1   # trailing comment\r\n"
                 "sphere 0 0 0 1 #no space needed\r\n"
                 "  #indented comment\n"
                 "sphere 1 1 1 2");  // no newline at the end
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  EXPECT_EQ(p.scene.table<Sphere>().size(), 3u);
  EXPECT_EQ(p.scene.table<Sphere>().r[2], 2.0f);
}

TEST(Parser, DoubleSlashIsNotAComment) {
  auto p = parse(std::string(kCameraLine) + "// not a comment\n");
  EXPECT_THAT(errors(p), ElementsAre("t.scn:2:1: unknown command '//'"));
}

TEST(Parser, CommandsAreCaseSensitive) {
  auto p = parse(std::string(kCameraLine) + "Sphere 0 0 0 1\n");
  EXPECT_THAT(errors(p), ElementsAre("t.scn:2:1: unknown command 'Sphere'"));
}

TEST(Parser, StrictNumbers) {
  auto p = parse(std::string(kCameraLine) +
                 "sphere 0 0 2.900874b 1\n"
                 "sphere 0 zero 0 1\n"
                 "sphere 0 0 nan 1\n"
                 "sphere 0 0 0 inf\n"
                 "sphere 1e39 0 0 1\n"
                 "sphere 0 0 1e400 1\n"
                 "sphere 0,0 0 0 1\n"
                 "sphere +1 -2 3e-1 .5\n");
  EXPECT_THAT(errors(p), ElementsAre("t.scn:2:12: expected a number, found '2.900874b'",
                                     "t.scn:3:10: expected a number, found 'zero'",
                                     "t.scn:4:12: expected a finite number, found 'nan'",
                                     "t.scn:5:14: expected a finite number, found 'inf'",
                                     "t.scn:6:8: number '1e39' does not fit in a float",
                                     "t.scn:7:12: number '1e400' is out of range",
                                     "t.scn:8:8: expected a number, found '0,0'"));
  ASSERT_EQ(p.scene.table<Sphere>().size(), 1u);
  EXPECT_EQ(p.scene.table<Sphere>().center(0), Vec3f(1, -2, 0.3f));
  EXPECT_EQ(p.scene.table<Sphere>().r[0], 0.5f);
}

TEST(Parser, LenientTakesNumericPrefixWithWarning) {
  auto p = parse(std::string(kCameraLine) + "sphere 0 0 2.900874b 1\n", true);
  EXPECT_TRUE(p.ok());
  EXPECT_THAT(warnings(p),
              ElementsAre("t.scn:2:12: warning: took the number 2.900874 from '2.900874b'",
                          "t.scn:2:1: warning: sphere before any material line: using grey "
                          "diffuse (Kd 0.5, no specular)",
                          "t.scn: warning: no screen line: using 400x300"));
  ASSERT_EQ(p.scene.table<Sphere>().size(), 1u);
  EXPECT_EQ(p.scene.table<Sphere>().cz[0], 2.900874f);
}

TEST(Parser, LenientSkipsBadLinesAndKeepsTheRest) {
  auto p = parse(std::string(kCameraLine) +
                     "sphere 0 0 0\n"
                     "bogus 1 2\n"
                     "sphere 0 0 0 1\n",
                 true);
  EXPECT_TRUE(p.ok());
  EXPECT_THAT(warnings(p),
              ElementsAre("t.scn:2:1: warning: sphere takes 4 numbers, found 3 (line skipped)",
                          "t.scn:3:1: warning: unknown command 'bogus' (line skipped)",
                          "t.scn:4:1: warning: sphere before any material line: using grey "
                          "diffuse (Kd 0.5, no specular)",
                          "t.scn: warning: no screen line: using 400x300"));
  EXPECT_EQ(p.scene.table<Sphere>().size(), 1u);
}

TEST(Parser, ParameterCounts) {
  auto p = parse(std::string(kCameraLine) +
                 "brdf 0.6 0.6 0.6 0 0 10 0 0 0 1.0\n"
                 "brdf 0.6 0.6 0.6 0 0 10 0 0 1.0\n"
                 "brdf 1 1 1 0 0 0\n"
                 "cylinder 1.2 1.2 0.0 0.0 0.4 0.05\n"
                 "box 0 0 0 1 1 1 1\n"
                 "light 1 1\n"
                 "ambient 1 1 1 1\n"
                 "screen 100\n"
                 "camera 1 2 3\n");
  EXPECT_THAT(errors(p), ElementsAre("t.scn:2:1: brdf takes 7 or 11 numbers, found 10",
                                     "t.scn:3:1: brdf takes 7 or 11 numbers, found 9",
                                     "t.scn:4:1: brdf takes 7 or 11 numbers, found 6",
                                     "t.scn:5:1: cylinder takes 7 numbers, found 6",
                                     "t.scn:6:1: box takes 6 numbers, found 7",
                                     "t.scn:7:1: light takes 3 numbers, found 2",
                                     "t.scn:8:1: ambient takes 3 numbers, found 4",
                                     "t.scn:9:1: screen takes 2 numbers, found 1",
                                     "t.scn:10:1: camera takes at least 4 numbers, found 3"));
}

TEST(Parser, ValueRules) {
  auto p = parse(std::string(kCameraLine) +
                 "sphere 0 0 0 0\n"
                 "sphere 0 0 0 -1\n"
                 "box 0 0 0 1 0 1\n"
                 "cylinder 0 0 0 0 0 0 1\n"
                 "cylinder 0 0 0 0 0 1 0\n"
                 "brdf 0.5 0.5 0.5 0 0 0 -1\n"
                 "brdf 0.5 0.5 0.5 0 0 0 1 0 0 0 0\n"
                 "brdf -0.5 0.5 0.5 0 0 0 1\n"
                 "light 1 -1 1\n"
                 "screen 0 10\n"
                 "screen 10.5 10\n"
                 "screen 65536 8192\n"
                 "camera 0 0 0 0\n"
                 "sphere 0 0 0 1e-46\n");
  EXPECT_THAT(
      errors(p),
      ElementsAre("t.scn:2:14: sphere radius must be > 0", "t.scn:3:14: sphere radius must be > 0",
                  "t.scn:4:13: box diagonal components must be non-zero",
                  "t.scn:5:16: cylinder axis must be non-zero",
                  "t.scn:6:22: cylinder radius must be > 0", "t.scn:7:24: brdf alpha must be >= 0",
                  "t.scn:8:32: brdf ior must be > 0",
                  "t.scn:9:6: brdf colours (Kd, Ks, Kt) must be >= 0",
                  "t.scn:10:7: light radiance must be >= 0",
                  "t.scn:11:8: screen size must be a whole number >= 1",
                  "t.scn:12:8: screen size must be a whole number >= 1",
                  "t.scn:13:8: screen has more than 2^28 pixels",
                  "t.scn:14:14: camera ry must be > 0", "t.scn:15:14: sphere radius must be > 0"));
  EXPECT_EQ(p.scene.primitive_count(), 0u);
  // A rejected shape leaves no default material behind.
  EXPECT_TRUE(p.scene.materials.empty());
}

TEST(Parser, NegativeBoxDiagonalIsTheSameBox) {
  auto p = parse(std::string(kCameraLine) + "box 1 1 1 -2 3 -0.5\n");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p.scene.table<Box>().lo(0), Vec3f(-1, 1, 0.5f));
  EXPECT_EQ(p.scene.table<Box>().hi(0), Vec3f(1, 4, 1));
}

TEST(Parser, MissingCameraIsAnErrorMissingScreenAWarning) {
  auto p = parse("sphere 0 0 0 1\n");
  EXPECT_THAT(errors(p), ElementsAre("t.scn: no camera line"));
  EXPECT_THAT(warnings(p),
              ElementsAre("t.scn:1:1: warning: sphere before any material line: using grey "
                          "diffuse (Kd 0.5, no specular)",
                          "t.scn: warning: no screen line: using 400x300"));
  EXPECT_EQ(p.scene.width, 400u);
  EXPECT_EQ(p.scene.height, 300u);
}

TEST(Parser, RepeatedSettingsLastWinsWithWarning) {
  auto p = parse(
      "screen 10 10\ncamera 0 0 1 1\nscreen 20 30\nambient 1 1 1\nambient 2 2 2\n"
      "camera 0 0 2 1\n");
  EXPECT_TRUE(p.ok());
  EXPECT_THAT(warnings(p),
              ElementsAre("t.scn:3:1: warning: screen given again (first on line 1): the last "
                          "one wins",
                          "t.scn:5:1: warning: ambient given again (first on line 4): the last "
                          "one wins",
                          "t.scn:6:1: warning: camera given again (first on line 2): the last "
                          "one wins"));
  EXPECT_EQ(p.scene.width, 20u);
  EXPECT_EQ(p.scene.height, 30u);
  EXPECT_EQ(p.scene.ambient, Vec3f(2, 2, 2));
  EXPECT_EQ(p.scene.camera->eye.z, 2.0);
}

TEST(Parser, ShapeBeforeMaterialGetsDefaultGreyOnce) {
  auto p = parse(std::string(kCameraLine) + "screen 4 3\nsphere 0 0 0 1\nbox 0 0 0 1 1 1\n");
  EXPECT_TRUE(p.ok());
  EXPECT_EQ(warnings(p).size(), 1u);
  ASSERT_EQ(p.scene.materials.size(), 1u);
  EXPECT_EQ(p.scene.materials[0].kd, Vec3f(0.5f, 0.5f, 0.5f));
  EXPECT_EQ(p.scene.materials[0].ks, Vec3f(0, 0, 0));
  EXPECT_EQ(p.scene.table<Box>().material[0], 0u);
}

TEST(Parser, ShapesTakeTheLatestMaterial) {
  auto p = parse(std::string(kCameraLine) +
                 "brdf 1 0 0 0 0 0 1\nsphere 0 0 0 1\nlight 1 1 1\nbrdf 0 1 0 0 0 0 1\n"
                 "sphere 0 0 0 1\n");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p.scene.table<Sphere>().material[0], 0u);
  EXPECT_EQ(p.scene.table<Sphere>().material[1], 2u);
  EXPECT_TRUE(p.scene.lights.empty());
}

TEST(Parser, ReportsEveryErrorOfTheFile) {
  auto p = parse("sphere 1\nbox 1\ncylinder 1\n");
  EXPECT_EQ(p.diagnostics.error_count(), 4);  // three lines and the missing camera
}

TEST(Parser, OverlongLineIsAnError) {
  std::string text =
      std::string(kCameraLine) + "sphere 0 0 0 1 " + std::string(kMaxLineBytes, ' ') + "\n";
  auto p = parse(text);
  EXPECT_THAT(errors(p), ElementsAre("t.scn:2:65537: expected a line of at most 65536 bytes, "
                                     "found 65551 bytes"));
}

TEST(Parser, BinaryGarbageGivesErrorsNotACrash) {
  std::string text;
  for (int i = 0; i < 4096; ++i)
    text.push_back(char((i * 7919) % 256));
  auto p = parse(text);
  EXPECT_FALSE(p.ok());
}

TEST(Parser, MissingSceneFileIsAnError) {
  auto p = load_scene_file("no/such/scene.scn");
  ASSERT_EQ(p.diagnostics.error_count(), 1);
  EXPECT_EQ(to_string(p.diagnostics.items[0]).rfind("no/such/scene.scn: cannot read", 0), 0u);
}

TEST(SplitTokens, ColumnsAreOneBased) {
  std::vector<Token> t;
  split_tokens("  ab\tc  #d e", t);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].text, "ab");
  EXPECT_EQ(t[0].col, 3);
  EXPECT_EQ(t[1].text, "c");
  EXPECT_EQ(t[1].col, 6);
}

}  // namespace
}  // namespace raylane
