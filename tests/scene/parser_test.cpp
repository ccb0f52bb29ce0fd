// The scene language, rule by rule (docs/scene-language.md).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scene/hints.h"
#include "scene/scene_test_util.h"
#include "support/paths.h"

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
  EXPECT_EQ(s.camera->eye, glm::dvec3(1, 2, 3));
  EXPECT_EQ(s.camera->ry, 0.5);
  EXPECT_EQ(s.ambient, glm::vec3(0.1f, 0.2f, 0.3f));
  ASSERT_EQ(s.materials.size(), 3u);
  EXPECT_TRUE(s.materials[0].is_light);
  EXPECT_EQ(s.materials[0].emission, glm::vec3(5, 6, 7));
  EXPECT_EQ(s.materials[1].kd, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.materials[1].ks, glm::vec3(0.4f, 0.5f, 0.6f));
  EXPECT_EQ(s.materials[1].alpha, 20.0f);
  EXPECT_EQ(s.materials[1].kt, glm::vec3(0, 0, 0));
  EXPECT_EQ(s.materials[1].ior, 1.0f);
  EXPECT_EQ(s.materials[2].kt, glm::vec3(0.7f, 0.8f, 0.9f));
  EXPECT_EQ(s.materials[2].ior, 1.5f);
  ASSERT_EQ(s.table<Sphere>().size(), 1u);
  EXPECT_EQ(s.table<Sphere>().material[0], 0u);
  ASSERT_EQ(s.table<Box>().size(), 1u);
  EXPECT_EQ(s.table<Box>().hi(0), glm::vec3(1, 2, 3));
  EXPECT_EQ(s.table<Box>().material[0], 1u);
  ASSERT_EQ(s.table<Cylinder>().size(), 1u);
  EXPECT_EQ(s.table<Cylinder>().material[0], 2u);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0], PrimRef(tag_of<Sphere>, 0));
  EXPECT_EQ(s.primitive_count(), 3u);
}

TEST(Parser, LensTakesRadiusAndFocusAndTheLastLineWins) {
  auto p = parse(std::string(kCameraLine) + "lens 0.1 3\nlens 0.05 2.5\n");
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  EXPECT_EQ(p.scene.lens.radius, 0.05);
  EXPECT_EQ(p.scene.lens.focus, 2.5);
  int repeats = 0;
  for (const std::string& w : warnings(p))
    repeats += w == "t.scn:3:1: warning: lens given again (first on line 2): the last one wins";
  EXPECT_EQ(repeats, 1);
  EXPECT_EQ(parse(kCameraLine).scene.lens.radius, 0);  // the pinhole by default
  EXPECT_THAT(errors(parse(std::string(kCameraLine) + "lens -0.1 3\n")),
              ElementsAre("t.scn:2:6: lens radius must be >= 0 (0 is the pinhole)"));
  EXPECT_THAT(errors(parse(std::string(kCameraLine) + "lens 0.1 0\n")),
              ElementsAre("t.scn:2:10: lens focus distance must be > 0"));
  EXPECT_EQ(errors(parse(std::string(kCameraLine) + "lens 0.1\n")).size(), 1u);
  EXPECT_EQ(errors(parse(std::string(kCameraLine) + "lens 0.1 2 3\n")).size(), 1u);
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
  EXPECT_THAT(errors(p), ElementsAre("t.scn:2:1: unknown command 'Sphere'; did you mean "
                                     "'sphere'? (commands are lower case)"));
}

// The hints of docs/scene-language.md, "Hints": a near miss by edit distance, none where two
// commands are as near or none is near enough.
TEST(Parser, AMisspeltCommandIsNamedByItsNearestCommand) {
  auto p = parse(std::string(kCameraLine) +
                 "shpere 0 0 0 1\ncylnder 0 0 0 0 0 1 1\nBRDF 1 1 1 0 0 0 1\n");
  EXPECT_THAT(errors(p),
              ElementsAre("t.scn:2:1: unknown command 'shpere'; did you mean 'sphere'?",
                          "t.scn:3:1: unknown command 'cylnder'; did you mean 'cylinder'?",
                          "t.scn:4:1: unknown command 'BRDF'; did you mean 'brdf'? (commands are "
                          "lower case)"));
  // 'bogus' is two edits from 'torus' and 'lx' two from 'box', where their lengths allow one:
  // nothing is offered.
  auto far = parse(std::string(kCameraLine) + "bogus 1\nlx 1\n");
  EXPECT_THAT(errors(far),
              ElementsAre("t.scn:2:1: unknown command 'bogus'", "t.scn:3:1: unknown command 'lx'"));
}

TEST(Parser, EditDistanceCountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(edit_distance("sphere", "sphere"), 0u);
  EXPECT_EQ(edit_distance("shpere", "sphere"), 2u);  // a swap is two substitutions
  EXPECT_EQ(edit_distance("cylnder", "cylinder"), 1u);
  EXPECT_EQ(edit_distance("", "box"), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
}

TEST(Parser, CommasBetweenNumbersAreNamed) {
  auto p = parse(std::string(kCameraLine) + "sphere 1, 2, 3, 0.5\nsphere 1,2,3 0.5\n");
  EXPECT_THAT(errors(p),
              ElementsAre("t.scn:2:8: expected a number, found '1,'; separate numbers with "
                          "spaces, not commas",
                          "t.scn:3:1: sphere takes 4 numbers, found 2; separate numbers with "
                          "spaces, not commas"));
  auto brdf = parse(std::string(kCameraLine) + "brdf 1,1,1 0 0 0 1\n");
  EXPECT_THAT(errors(brdf), ElementsAre("t.scn:2:1: brdf takes 7 or 11 numbers, found 5; "
                                        "separate numbers with spaces, not commas"));
  // A number that is wrong for another reason gets no hint.
  auto plain = parse(std::string(kCameraLine) + "sphere 1 2 3 0.5x\n");
  EXPECT_THAT(errors(plain), ElementsAre("t.scn:2:14: expected a number, found '0.5x'"));
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
  EXPECT_THAT(
      errors(p),
      ElementsAre("t.scn:2:12: expected a number, found '2.900874b'",
                  "t.scn:3:10: expected a number, found 'zero'",
                  "t.scn:4:12: expected a finite number, found 'nan'",
                  "t.scn:5:14: expected a finite number, found 'inf'",
                  "t.scn:6:8: number '1e39' does not fit in a float",
                  "t.scn:7:12: number '1e400' does not fit in a float",
                  "t.scn:8:8: expected a number, found '0,0'; separate numbers with spaces, not "
                  "commas"));
  ASSERT_EQ(p.scene.table<Sphere>().size(), 1u);
  EXPECT_EQ(p.scene.table<Sphere>().center(0), glm::vec3(1, -2, 0.3f));
  EXPECT_EQ(p.scene.table<Sphere>().r[0], 0.5f);
}

// Numbers too small for a double underflow to 0, accepted where 0 is (the spec's rule); a
// radius positive in the text but 0 in float says so; a tiny rotation axis is still an axis.
TEST(Parser, TinyNumbers) {
  auto p = parse(std::string(kCameraLine) +
                 "sphere 1e-400 -1e-400 0 1\n"
                 "sphere 0 0 0 1e-46\n"
                 "cylinder 0 0 0 0 0 1 1e-46\n"
                 "sphere 0 0 0 1e-400\n"
                 "camera 0 0 5 0.5 a 90 1e-200 1e-200 1e-200\n");
  EXPECT_THAT(errors(p),
              ElementsAre("t.scn:3:14: sphere radius rounds to 0 in single precision; it must be > "
                          "0 after rounding (at least about 1.4e-45)",
                          "t.scn:4:22: cylinder radius rounds to 0 in single precision; it must "
                          "be > 0 after rounding (at least about 1.4e-45)",
                          "t.scn:5:14: sphere radius must be > 0"));
  ASSERT_EQ(p.scene.table<Sphere>().size(), 1u);
  EXPECT_EQ(p.scene.table<Sphere>().center(0), glm::vec3(0, 0, 0));
  ASSERT_TRUE(p.scene.camera);  // the axis (1, 1, 1)/√3, not "must be non-zero"
  EXPECT_NEAR(p.scene.camera->rotation[0][0], 1.0 / 3, 1e-12);
}

// Invisible bytes are shown escaped, pointed at and explained (docs/scene-language.md, "Numbers").
TEST(Parser, InvisibleBytesAreShownAndExplained) {
  auto nbsp = parse(std::string(kCameraLine) + "sphere 0 0 0\xC2\xA0 1\n");
  EXPECT_THAT(errors(nbsp),
              ElementsAre("t.scn:2:13: expected a number, found '0\\u00A0', which holds a "
                          "no-break space (\\u00A0): write numbers with plain ASCII digits and "
                          "separate them with spaces"));
  auto vt = parse(std::string(kCameraLine) + "sphere 0 0 \v0 1\n");
  ASSERT_EQ(errors(vt).size(), 1u);
  EXPECT_NE(errors(vt)[0].find("t.scn:2:12: expected a number, found '\\x0B0', which holds a "
                               "vertical tab (\\x0B)"),
            std::string::npos)
      << errors(vt)[0];
  auto bom = parse(std::string("\xEF\xBB\xBF") + kCameraLine);
  EXPECT_TRUE(bom.ok());
  ASSERT_EQ(warnings(bom).size(), 2u);  // the BOM, and no screen line
  EXPECT_NE(warnings(bom)[0].find(
                "t.scn:1:1: warning: skipped the UTF-8 byte-order mark \\xEF\\xBB\\xBF"),
            std::string::npos)
      << warnings(bom)[0];
  auto cr = parse("camera 0 0 5 0.5\rsphere 0 0 0 1\r");
  ASSERT_EQ(errors(cr).size(), 1u);
  EXPECT_NE(errors(cr)[0].find("t.scn:1:17: the lines of this file end in CR only"),
            std::string::npos)
      << errors(cr)[0];
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
                  "t.scn:13:8: screen has 536870912 pixels; the limit is 2^28 (268435456) pixels",
                  "t.scn:14:14: camera ry must be > 0",
                  "t.scn:15:14: sphere radius rounds to 0 in single precision; it must be > 0 "
                  "after rounding (at least about 1.4e-45)"));
  EXPECT_EQ(p.scene.primitive_count(), 0u);
  // A rejected shape leaves no default material behind.
  EXPECT_TRUE(p.scene.materials.empty());
}

TEST(Parser, NegativeBoxDiagonalIsTheSameBox) {
  auto p = parse(std::string(kCameraLine) + "box 1 1 1 -2 3 -0.5\n");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p.scene.table<Box>().lo(0), glm::vec3(-1, 1, 0.5f));
  EXPECT_EQ(p.scene.table<Box>().hi(0), glm::vec3(1, 4, 1));
}

TEST(Parser, ARejectedCameraLineIsTheOnlyErrorNotAlsoAMissingCamera) {
  auto p = parse("screen 4 3\ncamera 0 -6 0 -1\n");
  EXPECT_THAT(errors(p), ElementsAre("t.scn:2:15: camera ry must be > 0"));
  // --lenient skips the line, so the scene has no camera: that error stays, naming the line.
  auto lenient = parse("screen 4 3\ncamera 0 -6 0 -1\n", true);
  EXPECT_THAT(errors(lenient),
              ElementsAre("t.scn: no camera line (the one at t.scn:2 was skipped)"));
  // A later good camera line makes the scene whole; an earlier one does too.
  EXPECT_TRUE(parse("camera 0 -6 0 -1\ncamera 0 -6 0 1\n", true).ok());
  EXPECT_THAT(errors(parse("camera 0 -6 0 1\ncamera 0 -6 0 -1\n")),
              ElementsAre("t.scn:2:15: camera ry must be > 0"));
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
  EXPECT_EQ(p.scene.ambient, glm::vec3(2, 2, 2));
  EXPECT_EQ(p.scene.camera->eye.z, 2.0);
}

TEST(Parser, ShapeBeforeMaterialGetsDefaultGreyOnce) {
  auto p = parse(std::string(kCameraLine) + "screen 4 3\nsphere 0 0 0 1\nbox 0 0 0 1 1 1\n");
  EXPECT_TRUE(p.ok());
  EXPECT_EQ(warnings(p).size(), 1u);
  ASSERT_EQ(p.scene.materials.size(), 1u);
  EXPECT_EQ(p.scene.materials[0].kd, glm::vec3(0.5f, 0.5f, 0.5f));
  EXPECT_EQ(p.scene.materials[0].ks, glm::vec3(0, 0, 0));
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

// File names may be quoted to hold spaces (docs/scene-language.md, "Lines and tokens").
TEST(SplitTokens, QuotedFileNames) {
  std::vector<Token> t;
  ASSERT_FALSE(split_tokens(R"(mesh "my models/a \"b\" \\.ply" 1 2)", t));
  ASSERT_EQ(t.size(), 4u);
  EXPECT_TRUE(t[1].quoted);
  EXPECT_EQ(t[1].name(), R"(my models/a "b" \.ply)");
  EXPECT_EQ(t[2].text, "1");
  EXPECT_EQ(t[2].col, 33);
  // Outside a file-name position a quote is an ordinary character.
  ASSERT_FALSE(split_tokens(R"(sphere "1 2)", t));
  EXPECT_EQ(t.size(), 3u);
  EXPECT_FALSE(t[1].quoted);
  auto unclosed = split_tokens(R"(mesh "a b.ply 0 0 0 1)", t);
  ASSERT_TRUE(unclosed);
  EXPECT_EQ(unclosed->col, 6);
  auto junk = split_tokens(R"(mesh "a.ply"junk 0 0 0 1)", t);
  ASSERT_TRUE(junk);
  EXPECT_EQ(junk->col, 13);
  auto nul = split_tokens(std::string_view("mesh a\0b", 8), t);
  ASSERT_TRUE(nul);
  EXPECT_EQ(nul->col, 7);
}

TEST(Parser, MeshInAFolderWithSpaces) {
  std::string dir = testing::temp_dir();
  std::filesystem::create_directories(dir + "/my models");
  std::filesystem::copy_file(testing::source_path("scenes/letterX.ply"),
                             dir + "/my models/letter x.ply");
  std::ofstream(dir + "/s.scn") << kCameraLine << "mesh \"my models/letter x.ply\" 0 0 0 1\n";
  auto p = load_scene_file(dir + "/s.scn");
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  EXPECT_GT(p.scene.table<Triangle>().size(), 0u);
  ASSERT_EQ(p.meshes.size(), 1u);
  EXPECT_EQ(p.meshes[0].file, "my models/letter x.ply");
  std::ofstream(dir + "/bad.scn") << kCameraLine << "mesh \"my models/letter x.ply 0 0 0 1\n";
  auto bad = load_scene_file(dir + "/bad.scn");
  ASSERT_EQ(bad.diagnostics.error_count(), 1);
  EXPECT_NE(errors(bad)[0].find(":2:6: expected a closing quote"), std::string::npos)
      << errors(bad)[0];
}

// `mesh my models/letter x.ply 0 0 0 1` without quotes: the joined name is a file, so the
// error says so and how to mend it; the same for texture and environment.
TEST(Parser, AnUnquotedFileNameWithASpaceIsNamed) {
  std::string dir = testing::temp_dir();
  std::filesystem::copy_file(testing::source_path("scenes/letterX.ply"), dir + "/letter x.ply",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir + "/s.scn") << kCameraLine << "mesh letter x.ply 0 0 0 1\n"
                                << "brdf 1 1 1 0 0 0 1\ntexture letter x.ply\n"
                                << "environment letter x.ply 1\n";
  ParseOptions lenient;
  lenient.lenient = true;
  auto p = load_scene_file(dir + "/s.scn", lenient);
  std::vector<std::string> w = warnings(p);
  ASSERT_EQ(w.size(), 4u);  // and "no screen line"
  EXPECT_NE(
      w[0].find(":2:13: warning: expected a number (tx) after the file name, found 'x.ply'; the "
                "file name 'letter x.ply' holds a space: quote it, \"letter x.ply\""),
      std::string::npos)
      << w[0];
  EXPECT_NE(
      w[1].find(":4:16: warning: texture takes one file name, found 2 parameters; the file name "
                "'letter x.ply' holds a space: quote it"),
      std::string::npos)
      << w[1];
  EXPECT_NE(
      w[2].find(":5:20: warning: expected a number (s) after the file name, found 'x.ply'; the "
                "file name 'letter x.ply' holds a space"),
      std::string::npos)
      << w[2];
  // No such file with the space either: the plain error, no hint.
  std::ofstream(dir + "/t.scn") << kCameraLine << "mesh letter y.ply 0 0 0 1\n";
  auto none = load_scene_file(dir + "/t.scn");
  ASSERT_EQ(none.diagnostics.error_count(), 1);
  EXPECT_EQ(errors(none)[0].find("holds a space"), std::string::npos) << errors(none)[0];
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
