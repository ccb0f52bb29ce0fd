// The orientation mini-language: forms, right-multiplied composition, normalisation, errors.
#include <gtest/gtest.h>

#include <cmath>

#include "raylane/scene/orientation.h"
#include "scene/scene_test_util.h"

namespace raylane {
namespace {

using ::testing::ElementsAre;
using testing::errors;
using testing::parse;

glm::dmat3 camera_rotation(const std::string& orientation) {
  auto p = parse("camera 0 0 0 1 " + orientation + "\n");
  EXPECT_TRUE(p.ok()) << errors(p)[0];
  return p.ok() ? p.scene.camera->rotation : glm::dmat3();
}

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tol = 1e-12) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Orientation, EmptyIsIdentity) {
  glm::dmat3 r = camera_rotation("");
  expect_near(r * glm::dvec3(1, 2, 3), glm::dvec3(1, 2, 3), 0);
}

TEST(Orientation, AxisRotationsFollowTheRightHandRule) {
  expect_near(camera_rotation("x 90") * glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1));
  expect_near(camera_rotation("y 90") * glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0));
  expect_near(camera_rotation("z 90") * glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0));
  expect_near(camera_rotation("a 90 0 0 5") * glm::dvec3(1, 0, 0),
              glm::dvec3(0, 1, 0));  // axis normalised
}

TEST(Orientation, QuaternionIsNormalisedWFirst) {
  expect_near(camera_rotation("q 3 0 0 0") * glm::dvec3(1, 2, 3), glm::dvec3(1, 2, 3));
  // 90 degrees about z: (cos 45, 0, 0, sin 45), scaled by 2.
  double c = 2 * std::sqrt(0.5);
  expect_near(
      camera_rotation("q " + std::to_string(c) + " 0 0 " + std::to_string(c)) * glm::dvec3(1, 0, 0),
      glm::dvec3(0, 1, 0), 1e-6);
}

// "x 90 y 30 is R = Rx(90)·Ry(30): the last-listed rotation acts first."
TEST(Orientation, ComposesByRightMultiplication) {
  glm::dmat3 r = camera_rotation("x 90 y 30");
  glm::dmat3 expected = rotation_axis_angle({1, 0, 0}, 90) * rotation_axis_angle({0, 1, 0}, 30);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(r[j][i], expected[j][i], 1e-15);
  // And not the other order.
  glm::dmat3 wrong = rotation_axis_angle({0, 1, 0}, 30) * rotation_axis_angle({1, 0, 0}, 90);
  EXPECT_GT(std::abs(r[1][0] - wrong[1][0]) + std::abs(r[0][2] - wrong[0][2]), 0.1);
}

// The course's bunny line stands the PLY bunny's +Y up along world +Z.
TEST(Orientation, CourseBunnyLineMapsYToZ) {
  glm::dmat3 r = camera_rotation("z -90 q 0 0 0.707107 0.707106");
  // The line's quaternion is rounded to 6 digits: 1e-5 covers it.
  expect_near(r * glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), 1e-5);
}

TEST(Orientation, Errors) {
  auto p = parse(
      "camera 0 0 0 1 q 0 0 0 0\n"
      "camera 0 0 0 1 a 30 0 0 0\n"
      "camera 0 0 0 1 x 90 w 3\n"
      "camera 0 0 0 1 q 1 0 0\n"
      "camera 0 0 0 1 x\n"
      "camera 0 0 0 1 y abc\n");
  EXPECT_THAT(errors(p), ElementsAre("t.scn:1:16: quaternion must be non-zero",
                                     "t.scn:2:16: rotation axis must be non-zero",
                                     "t.scn:3:21: expected a rotation (x, y, z, a or q), found 'w'",
                                     "t.scn:4:16: rotation 'q' takes 4 numbers, found 3",
                                     "t.scn:5:16: rotation 'x' takes 1 number, found 0",
                                     "t.scn:6:18: expected a number, found 'abc'"));
}

TEST(Orientation, ALetterRunIntoItsNumberGetsTheSpacedHint) {
  auto p = parse(
      "camera 0 -6 0 0.5 x90\n"
      "camera 0 -6 0 0.5 z-30.5\n"
      "camera 0 -6 0 0.5 w3\n"
      "camera 0 -6 0 0.5 xy\n");
  EXPECT_THAT(errors(p),
              ElementsAre("t.scn:1:19: expected a rotation (x, y, z, a or q), found 'x90' (write "
                          "'x 90': the letter and its numbers are separate tokens)",
                          "t.scn:2:19: expected a rotation (x, y, z, a or q), found 'z-30.5' "
                          "(write 'z -30.5': the letter and its numbers are separate tokens)",
                          "t.scn:3:19: expected a rotation (x, y, z, a or q), found 'w3'",
                          "t.scn:4:19: expected a rotation (x, y, z, a or q), found 'xy'"));
}

}  // namespace
}  // namespace raylane
