// The `microfacet NAME` command (docs/scene-language.md, "microfacet"): it
// sets the current brdf material's distribution, for shapes before and after it; it is an error
// before any brdf line, after a light line, with a name it does not know or with another count
// of parameters (file:line:col); a repeat on one material warns and wins.
#include <gtest/gtest.h>

#include "raylane/scene/parser.h"
#include "scene/scene_test_util.h"

namespace raylane {
namespace {

using testing::errors;
using testing::warnings;

std::string scene(const std::string& lines) {
  return std::string(testing::kCameraLine) + "screen 4 4\n" + lines;
}

TEST(MicrofacetCommand, SetsTheCurrentBrdfMaterialsDistribution) {
  auto p = testing::parse(
      scene("brdf 0 0 0 1 1 1 20\nsphere 0 0 0 1\nmicrofacet ggx\nsphere 3 0 0 1\n"
            "brdf 0 0 0 1 1 1 20\nmicrofacet beckman\nsphere 6 0 0 1\n"
            "brdf 0 0 0 1 1 1 20\nsphere 9 0 0 1\nbrdf 0 0 0 1 1 1 20\nmicrofacet phong\n"
            "sphere 12 0 0 1\n"));
  ASSERT_TRUE(p.ok()) << ::testing::PrintToString(errors(p));
  EXPECT_TRUE(warnings(p).empty()) << ::testing::PrintToString(warnings(p));
  const auto& m = p.scene.materials;
  const SphereTable& s = p.scene.table<Sphere>();
  EXPECT_EQ(m[s.material[0]].microfacet, Microfacet::kGgx);  // a shape before the line too
  EXPECT_EQ(m[s.material[1]].microfacet, Microfacet::kGgx);
  EXPECT_EQ(m[s.material[2]].microfacet, Microfacet::kBeckman);
  EXPECT_EQ(m[s.material[3]].microfacet, Microfacet::kPhong);  // a new brdf starts as Phong
  EXPECT_EQ(m[s.material[4]].microfacet, Microfacet::kPhong);
}

TEST(MicrofacetCommand, RejectsEachBadLineAtItsColumn) {
  struct Case {
    std::string lines, message;
  };
  const Case cases[] = {
      {"microfacet ggx\n", "t.scn:3:1: microfacet before any brdf line"},
      {"sphere 0 0 0 1\nmicrofacet ggx\n", "t.scn:4:1: microfacet before any brdf line"},
      {"light 1 1 1\nmicrofacet ggx\n", "t.scn:4:1: microfacet after a light line"},
      {"brdf 0 0 0 1 1 1 20\nlight 1 1 1\nmicrofacet ggx\n",
       "t.scn:5:1: microfacet after a light line"},
      {"brdf 0 0 0 1 1 1 20\nmicrofacet\n",
       "t.scn:4:11: microfacet takes one name (phong, ggx or beckman), found 0 parameters"},
      {"brdf 0 0 0 1 1 1 20\nmicrofacet ggx beckman\n",
       "t.scn:4:16: microfacet takes one name (phong, ggx or beckman), found 2 parameters"},
      {"brdf 0 0 0 1 1 1 20\nmicrofacet GGX\n",
       "t.scn:4:12: microfacet takes phong, ggx or beckman, found 'GGX'"},
      {"brdf 0 0 0 1 1 1 20\nmicrofacet 1\n",
       "t.scn:4:12: microfacet takes phong, ggx or beckman, found '1'"},
      {"brdf 0 0 0 1 1 1 20\nmicrofacet beckmann\n",
       "t.scn:4:12: microfacet takes phong, ggx or beckman, found 'beckmann'"},
  };
  for (const Case& c : cases) {
    auto p = testing::parse(scene(c.lines));
    ASSERT_EQ(errors(p).size(), 1u) << c.lines << ::testing::PrintToString(errors(p));
    EXPECT_THAT(errors(p)[0], ::testing::HasSubstr(c.message)) << c.lines;
    // --lenient skips the line with a warning: every material keeps Phong.
    auto lenient = testing::parse(scene(c.lines), true);
    EXPECT_TRUE(lenient.ok()) << c.lines;
    std::string as_warning = c.message;
    as_warning.insert(as_warning.find(": ") + 2, "warning: ");
    EXPECT_THAT(::testing::PrintToString(warnings(lenient)), ::testing::HasSubstr(as_warning));
    for (const Material& m : lenient.scene.materials)
      EXPECT_EQ(m.microfacet, Microfacet::kPhong) << c.lines;
  }
}

TEST(MicrofacetCommand, ASecondLineOnOneMaterialWarnsAndReplacesTheFirst) {
  auto p = testing::parse(
      scene("brdf 0 0 0 1 1 1 20\nmicrofacet ggx\nsphere 0 0 0 1\nmicrofacet beckman\n"
            "brdf 0 0 0 1 1 1 20\nmicrofacet ggx\nsphere 3 0 0 1\n"));
  ASSERT_TRUE(p.ok()) << ::testing::PrintToString(errors(p));
  ASSERT_EQ(warnings(p).size(), 1u) << ::testing::PrintToString(warnings(p));
  EXPECT_THAT(warnings(p)[0],
              ::testing::HasSubstr("t.scn:6:1: warning: the material already has a microfacet "
                                   "line at t.scn:4:1: this one replaces it"));
  const SphereTable& s = p.scene.table<Sphere>();
  EXPECT_EQ(p.scene.materials[s.material[0]].microfacet, Microfacet::kBeckman);
  EXPECT_EQ(p.scene.materials[s.material[1]].microfacet, Microfacet::kGgx);
}

}  // namespace
}  // namespace raylane
