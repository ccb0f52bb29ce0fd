// `mbsphere x0 y0 z0 x1 y1 z1 r` (docs/scene-language.md, "mbsphere"): a row of the moving
// spheres' table, and the parser's error classes for it.
#include <gtest/gtest.h>

#include "scene/scene_test_util.h"

namespace raylane {
namespace {

using ::testing::ElementsAre;
using testing::errors;
using testing::kCameraLine;
using testing::parse;
using testing::warnings;

TEST(MbsphereCommand, AppendsTheStartTheMotionAndTheRadius) {
  auto p = parse(std::string(kCameraLine) +
                 "brdf 0.5 0.5 0.5 0 0 0 10\n"
                 "mbsphere 1 2 3 4 2 1 0.5\n"
                 "light 1 1 1\n"
                 "mbsphere 0 0 0 0 0 0 2\n");
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  const MovingSphereTable& t = p.scene.table<MovingSphere>();
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.start(0), glm::vec3(1, 2, 3));
  EXPECT_EQ(t.motion(0), glm::vec3(3, 0, -2));
  EXPECT_EQ(t.center_at(0, 0.5), glm::dvec3(2.5, 2, 2));
  EXPECT_EQ(t.r[0], 0.5f);
  EXPECT_EQ(t.material[0], 0u);
  EXPECT_EQ(t.motion(1), glm::vec3(0, 0, 0));
  // An emitting mbsphere is a light, as a sphere is.
  ASSERT_EQ(p.scene.lights.size(), 1u);
  EXPECT_EQ(p.scene.lights[0], PrimRef(tag_of<MovingSphere>, 1));
  EXPECT_TRUE(p.scene.moves());
  // The swept box: both end spheres' boxes.
  Bounds3f b = t.bounds(0);
  EXPECT_LE(b.lo.x, 0.5f);
  EXPECT_GE(b.hi.x, 4.5f);
  EXPECT_LE(b.lo.z, 0.5f);
  EXPECT_GE(b.hi.z, 3.5f);
  EXPECT_LT(b.hi.x, 4.5001f);
  EXPECT_GT(b.lo.x, 0.4999f);
}

TEST(MbsphereCommand, ASceneWithoutOneDoesNotMove) {
  auto p = parse(std::string(kCameraLine) + "sphere 0 0 0 1\n");
  ASSERT_TRUE(p.ok());
  EXPECT_FALSE(p.scene.moves());
}

// The classes of the other primitives' commands: count, numbers, underflow, the radius, the
// reach of float, each at file:line:col of the offending token; the rejected lines add no row.
TEST(MbsphereCommand, BadLinesSayWhereAndWhatAndAddNothing) {
  auto p = parse(std::string(kCameraLine) +
                 "mbsphere 0 0 0 1 1 1\n"
                 "mbsphere 0 0 0 1 1 1 1 1\n"
                 "mbsphere 0 0 0 1 1 x 1\n"
                 "mbsphere 0 0 0 1 nan 1 1\n"
                 "mbsphere 0 0 0 1 1 1e39 1\n"
                 "mbsphere 0 0 0 1 1 1 0\n"
                 "mbsphere 0 0 0 1 1 1 -2\n"
                 "mbsphere 0 0 0 1 1 1 1e-46\n"
                 "mbsphere 0 0 0 3e38 0 0 1e38\n"
                 "mbsphere -3e38 0 0 3e38 0 0 1\n"
                 "mbsphere 1e-400 0 0 0 -1e-400 0 1\n");
  EXPECT_THAT(errors(p),
              ElementsAre("t.scn:2:1: mbsphere takes 7 numbers, found 6",
                          "t.scn:3:1: mbsphere takes 7 numbers, found 8",
                          "t.scn:4:20: expected a number, found 'x'",
                          "t.scn:5:18: expected a finite number, found 'nan'",
                          "t.scn:6:20: number '1e39' does not fit in a float",
                          "t.scn:7:22: mbsphere radius must be > 0",
                          "t.scn:8:22: mbsphere radius must be > 0",
                          "t.scn:9:22: mbsphere radius rounds to 0 in single precision; it must "
                          "be > 0 after rounding (at least about 1.4e-45)",
                          "t.scn:10:16: mbsphere reaches beyond float (the largest is about "
                          "3.4e38)",
                          "t.scn:11:20: mbsphere moves beyond float (the largest is about "
                          "3.4e38)"));
  // Only the underflowing line (1e-400 is 0, accepted where 0 is) made a row.
  ASSERT_EQ(p.scene.table<MovingSphere>().size(), 1u);
  EXPECT_EQ(p.scene.table<MovingSphere>().start(0), glm::vec3(0, 0, 0));
  EXPECT_TRUE(p.scene.materials.size() == 1u);  // the grey default, for the accepted line
}

TEST(MbsphereCommand, LenientSkipsABadLine) {
  auto p = parse(std::string(kCameraLine) + "mbsphere 0 0 0 1 1 1\nmbsphere 0 0 0 1 1 1 1\n", true);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p.scene.table<MovingSphere>().size(), 1u);
  EXPECT_EQ(warnings(p).front(),
            "t.scn:2:1: warning: mbsphere takes 7 numbers, found 6 (line "
            "skipped)");
}

}  // namespace
}  // namespace raylane
