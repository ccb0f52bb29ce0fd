// `sdf` … `end` blocks (docs/scene-language.md, "SDF blocks"): the rows, leaves and
// programs they make, and every error the section lists.
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

std::vector<uint32_t> program(const SdfTable& t, uint32_t block) {
  auto b = t.program.begin() + t.program_begin[block];
  return {b, b + t.program_count[block]};
}

TEST(SdfCommand, ABlockIsOneRowWithItsLeavesAndPostfixProgram) {
  auto p =
      parse(scene("sdf\n"
                  "torus 0 0 0 0 0 2 1 0.25\n"
                  "brdf 0.1 0.2 0.3 0 0 0 10\n"
                  "sphere 1 0 0 0.5\n"
                  "smoothunion 0.2\n"
                  "box -2 -2 -2 4 4 2.5\n"
                  "intersection\n"
                  "cylinder 0 0 -3 0 0 6 0.5\n"
                  "smoothdifference 0.1\n"
                  "end\n"));
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  const SdfTable& t = p.scene.table<Sdf>();
  ASSERT_EQ(t.size(), 1u);
  EXPECT_THAT(t.leaf_kind, ElementsAre(kSdfTorus, kSdfSphere, kSdfBox, kSdfCylinder));
  EXPECT_THAT(program(t, 0),
              ElementsAre(0u, 1u, kSdfSmoothUnion, 2u, kSdfIntersect, 3u, kSdfSmoothDifference));
  EXPECT_THAT(t.program_k, ElementsAre(0.f, 0.f, 0.2f, 0.f, 0.f, 0.f, 0.1f));
  EXPECT_THAT(t.material, ElementsAre(0u, 1u, 1u, 1u));
  // The torus's axis is normalised.
  EXPECT_EQ(t.tori.uz[0], 1.f);
  // Bounds: ((torus ~∪ sphere) ∩ box) ~− cylinder: the box's z range and the union's x, y
  // (torus: ±1.25; the sphere reaches 1.5), widened by k = 0.2 and then by k = 0.1.
  EXPECT_NEAR(t.bounds(0).hi.x, 1.5 + 0.2 + 0.1, 1e-5);
  EXPECT_NEAR(t.bounds(0).lo.x, -1.25 - 0.2 - 0.1, 1e-5);
  EXPECT_NEAR(t.bounds(0).hi.z, 0.5 + 0.1, 1e-5);
  EXPECT_NEAR(t.bounds(0).lo.z, -0.5 - 0.2 - 0.1, 1e-5);
  EXPECT_EQ(p.scene.table<Sphere>().size() + p.scene.table<Box>().size(), 0u);
}

TEST(SdfCommand, SynonymsAreTheSameOperators) {
  auto p =
      parse(scene("sdf\nsphere 0 0 0 1\nsphere 1 0 0 1\nintersect\n"
                  "sphere 0 1 0 1\nsubtraction\nsphere 0 0 1 1\nunion\n"
                  "sphere 0 0 1 1\nsmoothintersect 0.5\nend\n"));
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  EXPECT_THAT(program(p.scene.table<Sdf>(), 0),
              ElementsAre(0u, 1u, kSdfIntersect, 2u, kSdfDifference, 3u, kSdfUnion, 4u,
                          kSdfSmoothIntersect));
}

TEST(SdfCommand, TwoBlocksKeepTheirOwnSlices) {
  auto p =
      parse(scene("sdf\nsphere 0 0 0 1\nend\nsdf\nbox 0 0 0 1 1 1\nsphere 3 0 0 1\n"
                  "union\nend\n"));
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  const SdfTable& t = p.scene.table<Sdf>();
  ASSERT_EQ(t.size(), 2u);
  EXPECT_THAT(t.leaf_begin, ElementsAre(0u, 1u));
  EXPECT_THAT(t.leaf_count, ElementsAre(1u, 2u));
  EXPECT_THAT(t.leaf_block, ElementsAre(0u, 1u, 1u));
  EXPECT_THAT(program(t, 1), ElementsAre(0u, 1u, kSdfUnion));
}

TEST(SdfCommand, TorusParametersAreChecked) {
  auto p =
      parse(scene("sdf\ntorus 0 0 0 0 0 0 1 0.5\ntorus 0 0 0 0 0 1 0 0\n"
                  "torus 0 0 0 0 0 1 1 -1\ntorus 0 0 0 0 0 1 1 2\nend\n"));
  auto e = errors(p);
  ASSERT_EQ(e.size(), 5u);
  EXPECT_EQ(e[0], "t.scn:5:13: torus axis must be non-zero");
  EXPECT_EQ(e[1], "t.scn:6:19: torus major radius R must be > 0");
  EXPECT_EQ(e[2], "t.scn:7:21: torus tube radius r must be > 0");
  EXPECT_EQ(e[3], "t.scn:8:21: torus tube radius r must be at most the major radius R");
  EXPECT_THAT(e[4], HasSubstr("expected exactly 1 solid on its stack, found 0"));
  EXPECT_EQ(p.scene.table<Sdf>().size(), 0u);
  EXPECT_EQ(p.scene.table<Sdf>().leaves(), 0u);
}

TEST(SdfCommand, SmoothWidthMustBeFiniteAndPositive) {
  auto p =
      parse(scene("sdf\nsphere 0 0 0 1\nsphere 1 0 0 1\nsmoothunion 0\n"
                  "smoothunion -1\nsmoothunion 1e-50\nsmoothunion 1e39\nsmoothunion\n"
                  "smoothunion nan\nsmoothunion inf\nsmoothunion 0.5\nend\n"));
  auto e = errors(p);
  ASSERT_EQ(e.size(), 7u);
  EXPECT_EQ(e[0], "t.scn:7:13: smoothunion width k must be > 0");
  EXPECT_EQ(e[1], "t.scn:8:13: smoothunion width k must be > 0");
  EXPECT_THAT(e[2], HasSubstr("t.scn:9:13: smoothunion width k rounds to 0"));
  EXPECT_EQ(e[3], "t.scn:10:13: number '1e39' does not fit in a float");
  EXPECT_EQ(e[4], "t.scn:11:1: smoothunion takes 1 number, found 0");
  EXPECT_EQ(e[5], "t.scn:12:13: expected a finite number, found 'nan'");
  EXPECT_EQ(e[6], "t.scn:13:13: expected a finite number, found 'inf'");
  EXPECT_EQ(p.scene.table<Sdf>().size(), 0u);  // a block with an error is dropped
}

TEST(SdfCommand, SdfOnlyLinesInACsgBlockAreErrors) {
  auto p =
      parse(scene("csg\nsphere 0 0 0 1\nsphere 1 0 0 1\nsmoothunion 0.5\n"
                  "torus 0 0 0 0 0 1 1 0.5\nunion\nend\n"));
  auto e = errors(p);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0],
            "t.scn:7:1: smoothunion belongs to sdf blocks only: not allowed inside the csg "
            "block opened at line 4");
  EXPECT_EQ(e[1],
            "t.scn:8:1: torus belongs to sdf blocks only: not allowed inside the csg block "
            "opened at line 4");
  EXPECT_EQ(p.scene.table<Csg>().size(), 0u);
}

TEST(SdfCommand, OperatorWithTooFewSolidsAndEndWithOtherThanOneAreErrors) {
  auto p =
      parse(scene("sdf\nsphere 0 0 0 1\nsmoothunion 1\nend\nsdf\nsphere 0 0 0 1\n"
                  "sphere 1 0 0 1\nend\n"));
  EXPECT_THAT(errors(p),
              ElementsAre("t.scn:6:1: smoothunion pops two solids: expected at least 2 on the "
                          "sdf block's stack, found 1",
                          "t.scn:11:1: end of the sdf block opened at line 8: expected exactly 1 "
                          "solid on its stack, found 2"));
  EXPECT_EQ(p.scene.table<Sdf>().size(), 0u);
  EXPECT_EQ(p.scene.table<Sdf>().leaves(), 0u);
}

TEST(SdfCommand, SdfWordsOutsideABlockAreErrors) {
  auto p = parse(scene("smoothdifference 1\ntorus 0 0 0 0 0 1 1 0.5\nend\n"));
  EXPECT_THAT(errors(p),
              ElementsAre("t.scn:4:1: smoothdifference outside a block: expected an sdf line "
                          "before it",
                          "t.scn:5:1: torus outside a block: expected an sdf line before it",
                          "t.scn:6:1: end outside a block: expected a csg or sdf line before it"));
}

TEST(SdfCommand, AFileEndingInsideABlockIsAnErrorAtItsSdfLine) {
  auto p = parse(scene("sphere 0 0 0 1\n  sdf\nsphere 0 0 0 1\nsphere 1 0 0 1\n"));
  EXPECT_THAT(errors(p), ElementsAre("t.scn:5:3: expected end for this sdf block, found the end "
                                     "of the input with 2 solids on its stack"));
  EXPECT_EQ(p.scene.table<Sdf>().size(), 0u);
  EXPECT_EQ(p.scene.table<Sdf>().leaves(), 0u);
  EXPECT_EQ(p.scene.table<Sphere>().size(), 1u);
}

TEST(SdfCommand, LinesThatCannotBeInABlockAreErrors) {
  auto p =
      parse(scene("sdf\nsphere 0 0 0 1\nlight 1 1 1\nmesh a.ply 0 0 0 1\ncamera 0 0 5 "
                  "0.5\ncsg\nsdf\nend\n"));
  auto e = errors(p);
  ASSERT_EQ(e.size(), 5u);
  EXPECT_EQ(e[0],
            "t.scn:6:1: 'light' is not allowed inside the sdf block opened at line 4: expected "
            "sphere, box, cylinder, torus, brdf, microfacet, union, intersect, difference, their "
            "smooth forms or end");
  EXPECT_THAT(e[1], HasSubstr("t.scn:7:1: 'mesh' is not allowed"));
  EXPECT_THAT(e[2], HasSubstr("t.scn:8:1: 'camera' is not allowed"));
  EXPECT_EQ(e[3],
            "t.scn:9:1: a csg block cannot be nested: expected end of the sdf block opened at "
            "line 4, found csg");
  EXPECT_EQ(e[4],
            "t.scn:10:1: a sdf block cannot be nested: expected end of the sdf block opened at "
            "line 4, found sdf");
}

TEST(SdfCommand, AnEmittingLeafIsAnError) {
  auto p = parse(std::string(kCameraLine) + "light 1 1 1\nsdf\ntorus 0 0 0 0 1 0 1 0.5\nend\n");
  auto e = errors(p);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0],
            "t.scn:4:1: an sdf leaf cannot emit: expected a brdf material, found the light "
            "made by the latest light line");
}

TEST(SdfCommand, MoreThanTheLeafLimitIsAnError) {
  std::string body = "sdf\n";
  for (uint32_t i = 0; i <= kSdfMaxLeaves; ++i)
    body += "sphere 0 0 0 1\n";
  body += "end\n";
  auto e = errors(parse(scene(body)));
  ASSERT_GE(e.size(), 1u);
  EXPECT_EQ(e[0], "t.scn:69:1: an sdf block holds at most 64 leaves, found one more");
}

TEST(SdfCommand, LenientSkipsABadBlockWholeAndKeepsTheRest) {
  auto p = parse(scene("sdf\nsphere 0 0 0 1\ntorus 0 0 0 0 0 1 1 2\nunion\nend\n"
                       "sdf\ntorus 0 0 0 0 0 1 1 0.5\nend\nsphere 3 0 0 1\n"),
                 /*lenient=*/true);
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  const SdfTable& t = p.scene.table<Sdf>();
  ASSERT_EQ(t.size(), 1u);
  EXPECT_THAT(t.leaf_kind, ElementsAre(kSdfTorus));  // the bad block's sphere is gone
  EXPECT_EQ(t.tori.size(), 1u);
  EXPECT_EQ(t.spheres.size(), 0u);
  EXPECT_THAT(program(t, 0), ElementsAre(0u));
  EXPECT_EQ(p.scene.table<Sphere>().size(), 1u);
  auto w = warnings(p);
  ASSERT_FALSE(w.empty());
  EXPECT_EQ(w.back(),
            "t.scn:8:1: warning: skipped the sdf block opened at line 4 whole: it has errors");
}

}  // namespace
}  // namespace raylane
