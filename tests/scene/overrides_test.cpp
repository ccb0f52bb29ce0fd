// `--set LINE` (docs/scene-language.md, "--set"): scene lines read after the file's own, under the
// file's rules, with diagnostics that name the override ("--set:N:COL").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "scene/scene_test_util.h"

namespace raylane {
namespace {

using ::testing::ElementsAre;

ParsedScene parse_with(const std::string& text, std::vector<std::string> overrides) {
  ParseOptions opts;
  opts.overrides = std::move(overrides);
  return parse_scene(text, "t.scn", opts);
}

TEST(Overrides, LastCameraAndScreenWinWithWarningsNamingBothPlaces) {
  auto p = parse_with("screen 400 300\ncamera 0 0 5 0.5\n",
                      {"screen 64 48", "camera 1 2 3 0.25", "screen 32 24"});
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p.scene.width, 32u);
  EXPECT_EQ(p.scene.height, 24u);
  EXPECT_EQ(p.scene.camera->eye, glm::dvec3(1, 2, 3));
  EXPECT_THAT(testing::messages(p, Severity::kWarning),
              ElementsAre("--set:1:1: warning: screen given again (first at t.scn:1): the last "
                          "one wins",
                          "--set:2:1: warning: camera given again (first at t.scn:2): the last "
                          "one wins",
                          "--set:3:1: warning: screen given again (first on line 1): the last "
                          "one wins"));
}

// An override may supply what the file lacks, and add shapes with the current material.
TEST(Overrides, SupplyWhatTheFileLacks) {
  auto p =
      parse_with("screen 4 3\nbrdf 0.5 0.5 0.5 0 0 0 1\n", {"camera 0 0 5 0.5", "sphere 0 0 0 1"});
  ASSERT_TRUE(p.ok()) << testing::errors(p).front();
  EXPECT_EQ(p.scene.table<Sphere>().size(), 1u);
}

TEST(Overrides, ErrorsNameTheOverrideAndTheColumn) {
  auto p = parse_with(std::string(testing::kCameraLine) + "screen 4 3\n",
                      {"screen 4 3", "sphere 0 0 x 1", "screen 4\n3"});
  EXPECT_THAT(testing::errors(p),
              ElementsAre(::testing::StartsWith("--set:2:12: "),
                          "--set:3:9: expected one scene line, found a line break"));
}

}  // namespace
}  // namespace raylane
