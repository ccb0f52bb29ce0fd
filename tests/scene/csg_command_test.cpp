// `csg` … `end` blocks (docs/scene-language.md, "CSG blocks"): the rows, leaves and programs they
// make, and every error the section lists.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "scene/scene_test_util.h"

namespace raylane {
namespace {

using ::testing::ElementsAre;
using testing::errors;
using ::testing::HasSubstr;
using testing::kCameraLine;
using testing::parse;
using testing::warnings;

std::string scene(const std::string& body) {
  return std::string(kCameraLine) + "screen 10 10\nbrdf 0.5 0.5 0.5 0 0 0 10\n" + body;
}

std::vector<uint32_t> program(const CsgTable& c, uint32_t block) {
  auto p = c.program_of(block);
  return {p.begin(), p.end()};
}

TEST(CsgCommand, ABlockIsOneRowWithItsLeavesAndPostfixProgram) {
  auto p =
      parse(scene("csg\n"
                  "sphere 0 0 0 1\n"
                  "brdf 0.1 0.2 0.3 0 0 0 10\n"
                  "box -2 -2 -2 4 4 4\n"
                  "intersect\n"
                  "cylinder 0 0 -3 0 0 6 0.5\n"
                  "difference\n"
                  "end\n"));
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  const CsgTable& c = p.scene.table<Csg>();
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c.leaves(), 3u);
  EXPECT_THAT(c.leaf_kind, ElementsAre(kCsgSphere, kCsgBox, kCsgCylinder));
  EXPECT_THAT(program(c, 0), ElementsAre(0u, 1u, kCsgIntersect, 2u, kCsgDifference));
  // Leaves take the current material; a brdf line inside changes it for the leaves after it.
  EXPECT_THAT(c.material, ElementsAre(0u, 1u, 1u));
  // The drill bounds the subtracted solid: its surface faces inward.
  EXPECT_THAT(c.leaf_flip, ElementsAre(0u, 0u, 1u));
  // Bounds: (sphere ∩ box) − cylinder is the sphere's box.
  SphereTable sphere;
  sphere.append(std::array<double, 4>{0, 0, 0, 1}, 0);
  EXPECT_EQ(c.bounds(0).lo, sphere.bounds(0).lo);
  EXPECT_EQ(c.bounds(0).hi, sphere.bounds(0).hi);
  // Nothing else became a primitive of its own.
  EXPECT_EQ(p.scene.table<Sphere>().size() + p.scene.table<Box>().size(), 0u);
}

TEST(CsgCommand, AMicrofacetLineInsideChangesTheCurrentMaterial) {
  auto p =
      parse(scene("csg\nsphere 0 0 0 1\nbrdf 0.2 0.2 0.2 0.5 0.5 0.5 100\nmicrofacet ggx\n"
                  "sphere 1 0 0 1\nunion\nend\n"));
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  const CsgTable& c = p.scene.table<Csg>();
  EXPECT_EQ(p.scene.materials[c.material[0]].microfacet, Microfacet::kPhong);
  EXPECT_EQ(p.scene.materials[c.material[1]].microfacet, Microfacet::kGgx);
}

TEST(CsgCommand, SynonymsAreTheSameOperators) {
  auto p =
      parse(scene("csg\nsphere 0 0 0 1\nsphere 1 0 0 1\nintersection\n"
                  "sphere 0 1 0 1\nsubtraction\nsphere 0 0 1 1\nunion\nend\n"));
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  EXPECT_THAT(program(p.scene.table<Csg>(), 0),
              ElementsAre(0u, 1u, kCsgIntersect, 2u, kCsgDifference, 3u, kCsgUnion));
}

TEST(CsgCommand, BoundsFollowTheOperators) {
  auto p =
      parse(scene("csg\nbox 0 0 0 2 2 2\nbox 1 1 1 2 2 2\nunion\nend\n"
                  "csg\nbox 0 0 0 2 2 2\nbox 1 1 1 2 2 2\nintersect\nend\n"
                  "csg\nbox 0 0 0 2 2 2\nbox 1 1 1 2 2 2\ndifference\nend\n"));
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  const CsgTable& c = p.scene.table<Csg>();
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c.bounds(0).lo, glm::vec3(0, 0, 0));
  EXPECT_EQ(c.bounds(0).hi, glm::vec3(3, 3, 3));
  EXPECT_EQ(c.bounds(1).lo, glm::vec3(1, 1, 1));
  EXPECT_EQ(c.bounds(1).hi, glm::vec3(2, 2, 2));
  EXPECT_EQ(c.bounds(2).lo, glm::vec3(0, 0, 0));
  EXPECT_EQ(c.bounds(2).hi, glm::vec3(2, 2, 2));
}

TEST(CsgCommand, AnIntersectionOfDisjointLeavesIsEmptyAndWarned) {
  auto p = parse(scene("csg\nsphere 0 0 0 1\nsphere 5 0 0 1\nintersect\nend\n"));
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  EXPECT_EQ(p.scene.table<Csg>().size(), 0u);
  EXPECT_THAT(warnings(p), ElementsAre("t.scn:4:1: warning: this csg block is empty (the bounds "
                                       "of its intersection are empty): nothing was added"));
}

TEST(CsgCommand, OperatorWithTooFewSolidsIsAnErrorNamingTheCount) {
  auto p = parse(scene("csg\nsphere 0 0 0 1\nunion\nend\n"));
  EXPECT_THAT(errors(p), ElementsAre("t.scn:6:1: union pops two solids: expected at least 2 on "
                                     "the csg block's stack, found 1"));
  EXPECT_EQ(p.scene.table<Csg>().size(), 0u);
}

TEST(CsgCommand, EndWithOtherThanOneSolidIsAnError) {
  auto p = parse(scene("csg\nsphere 0 0 0 1\nsphere 1 0 0 1\nend\ncsg\nend\n"));
  EXPECT_THAT(errors(p),
              ElementsAre("t.scn:7:1: end of the csg block opened at line 4: expected exactly 1 "
                          "solid on its stack, found 2",
                          "t.scn:9:1: end of the csg block opened at line 8: expected exactly 1 "
                          "solid on its stack, found 0"));
  EXPECT_EQ(p.scene.table<Csg>().size(), 0u);
}

TEST(CsgCommand, EndOrOperatorOutsideABlockIsAnError) {
  auto p = parse(scene("end\ndifference\n"));
  EXPECT_THAT(
      errors(p),
      ElementsAre("t.scn:4:1: end outside a block: expected a csg or sdf line before it",
                  "t.scn:5:1: difference outside a block: expected a csg or sdf line before it"));
}

TEST(CsgCommand, AFileEndingInsideABlockIsAnErrorAtItsCsgLine) {
  auto p = parse(scene("sphere 0 0 0 1\n  csg\nsphere 0 0 0 1\nsphere 1 0 0 1\n"));
  EXPECT_THAT(errors(p), ElementsAre("t.scn:5:3: expected end for this csg block, found the end "
                                     "of the input with 2 solids on its stack"));
  EXPECT_EQ(p.scene.table<Csg>().size(), 0u);
  EXPECT_EQ(p.scene.table<Sphere>().size(), 1u);  // the one before the block
}

TEST(CsgCommand, LinesThatCannotBeInABlockAreErrors) {
  auto p =
      parse(scene("csg\nsphere 0 0 0 1\nlight 1 1 1\nmesh a.ply 0 0 0 1\nmbsphere 0 0 0 1 "
                  "1 1 1\ncamera 0 0 5 0.5\nscreen 10 10\ncsg\nsdf\nend\n"));
  auto e = errors(p);
  ASSERT_EQ(e.size(), 7u);
  EXPECT_EQ(e[0],
            "t.scn:6:1: 'light' is not allowed inside the csg block opened at line 4: "
            "expected sphere, box, cylinder, brdf, microfacet, union, intersect, difference "
            "or end");
  EXPECT_THAT(e[1], HasSubstr("t.scn:7:1: 'mesh' is not allowed"));
  EXPECT_THAT(e[2], HasSubstr("t.scn:8:1: 'mbsphere' is not allowed"));
  EXPECT_THAT(e[3], HasSubstr("t.scn:9:1: 'camera' is not allowed"));
  EXPECT_THAT(e[4], HasSubstr("t.scn:10:1: 'screen' is not allowed"));
  EXPECT_EQ(e[5],
            "t.scn:11:1: a csg block cannot be nested: expected end of the csg block "
            "opened at line 4, found csg");
  EXPECT_EQ(e[6],
            "t.scn:12:1: a sdf block cannot be nested: expected end of the csg block "
            "opened at line 4, found sdf");
  EXPECT_EQ(p.scene.table<Csg>().size(), 0u);
}

TEST(CsgCommand, AnEmittingLeafIsAnError) {
  auto p = parse(std::string(kCameraLine) + "light 1 1 1\ncsg\nsphere 0 0 0 1\nend\n");
  auto e = errors(p);
  ASSERT_EQ(e.size(), 2u);  // and the block's end finds no solid
  EXPECT_EQ(e[0],
            "t.scn:4:1: a csg leaf cannot emit: expected a brdf material, found the light "
            "made by the latest light line");
  EXPECT_TRUE(p.scene.lights.empty());
}

TEST(CsgCommand, LeafParametersAreCheckedByTheirKind) {
  auto p = parse(scene("csg\nsphere 0 0 0 -1\nbox 0 0 0 1 0 1\ncylinder 0 0 0 0 0 1\nend\n"));
  auto e = errors(p);
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[0], "t.scn:5:14: sphere radius must be > 0");
  EXPECT_EQ(e[1], "t.scn:6:13: box diagonal components must be non-zero");
  EXPECT_THAT(e[2], HasSubstr("t.scn:7:1: cylinder takes 7 numbers"));
  EXPECT_THAT(e[3], HasSubstr("expected exactly 1 solid on its stack, found 0"));
}

TEST(CsgCommand, StrayParametersAreErrors) {
  auto p = parse(scene("csg 1\nsphere 0 0 0 1\nsphere 1 0 0 1\nunion x\nend 2\n"));
  EXPECT_THAT(errors(p), ElementsAre("t.scn:4:5: csg takes no parameters, found 1",
                                     "t.scn:7:7: union takes no parameters, found 1",
                                     "t.scn:8:5: end takes no parameters, found 1",
                                     "t.scn:8:1: end of the csg block opened at line 4: expected "
                                     "exactly 1 solid on its stack, found 2"));
}

TEST(CsgCommand, MoreThanTheLeafLimitIsAnError) {
  std::string body = "csg\n";
  for (uint32_t i = 0; i <= kCsgMaxLeaves; ++i)
    body += "sphere 0 0 0 1\n";
  body += "end\n";
  auto e = errors(parse(scene(body)));
  ASSERT_GE(e.size(), 1u);
  EXPECT_EQ(e[0], "t.scn:69:1: a csg block holds at most 64 leaves, found one more");
}

TEST(CsgCommand, LenientSkipsABadBlockWholeAndKeepsTheRest) {
  auto p = parse(scene("csg\nsphere 0 0 0 1\nsphere 0 0 0 -1\nunion\nend\n"
                       "csg\nsphere 0 0 0 1\nend\nsphere 3 0 0 1\n"),
                 /*lenient=*/true);
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  EXPECT_EQ(p.scene.table<Csg>().size(), 1u);
  EXPECT_EQ(p.scene.table<Sphere>().size(), 1u);
  auto w = warnings(p);
  ASSERT_FALSE(w.empty());
  EXPECT_EQ(w.back(),
            "t.scn:8:1: warning: skipped the csg block opened at line 4 whole: it has "
            "errors");
}

}  // namespace
}  // namespace raylane
