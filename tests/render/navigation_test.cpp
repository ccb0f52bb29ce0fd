// The viewer's camera math (view/navigation.h): quaternions back from matrices, orbit and fly
// moves, and the printed camera line read back by the scene parser.
#include "raylane/view/navigation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_access.hpp>
#include <random>

#include "raylane/scene/parser.h"
#include "support/paths.h"

namespace raylane {
namespace {

// The course scene's camera (scenes/testscene.scn): Z up, a little rolled.
CameraSpec course_camera() {
  CameraSpec c;
  c.eye = {5.553228, 2.942755, 2.900874};
  c.ry = 0.2;
  double n = std::sqrt(0.416981 * 0.416981 + 0.279589 * 0.279589 + 0.480987 * 0.480987 +
                       0.718247 * 0.718247);
  c.rotation = glm::mat3_cast(glm::dquat(0.416981 / n, 0.279589 / n, 0.480987 / n, 0.718247 / n));
  return c;
}

double max_difference(const glm::dmat3& a, const glm::dmat3& b) {
  double d = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      d = std::max(d, std::abs(a[j][i] - b[j][i]));
  return d;
}

// R·Rᵀ = I and det R = +1, to within `tol`.
void expect_rotation(const glm::dmat3& r, double tol) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(dot(glm::row(r, i), glm::row(r, j)), i == j ? 1.0 : 0.0, tol);
  EXPECT_NEAR(dot(cross(r[0], r[1]), r[2]), 1.0, tol);
}

glm::dquat random_unit_quaternion(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  glm::dquat q{g(rng), g(rng), g(rng), g(rng)};
  double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return {q.w / n, q.x / n, q.y / n, q.z / n};
}

TEST(Navigation, QuaternionFromRotationInvertsTheMatrix) {
  std::mt19937_64 rng(16);
  // Random rotations reach every branch (trace > 0, and each largest diagonal element), and
  // the half-turns about the axes have trace −1 exactly.
  std::vector<glm::dquat> qs = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  for (int i = 0; i < 2000; ++i)
    qs.push_back(random_unit_quaternion(rng));
  for (const glm::dquat& q : qs) {
    glm::dquat back = quaternion_from_rotation(glm::mat3_cast(glm::dquat(q.w, q.x, q.y, q.z)));
    double s = q.w < 0 ? -1 : 1;  // q and −q are one rotation; the answer has w ≥ 0
    EXPECT_GE(back.w, 0.0);
    EXPECT_NEAR(back.w, s * q.w, 1e-14);
    EXPECT_NEAR(back.x, s * q.x, 1e-14);
    EXPECT_NEAR(back.y, s * q.y, 1e-14);
    EXPECT_NEAR(back.z, s * q.z, 1e-14);
  }
}

TEST(Navigation, WorldUpIsTheAxisNearestTheCameraUp) {
  EXPECT_EQ(world_up_for(course_camera()), glm::dvec3(0, 0, 1));
  EXPECT_EQ(world_up_for(CameraSpec{}), glm::dvec3(0, 1, 0));  // identity: +y up
  CameraSpec upside_down;
  upside_down.rotation = rotation_axis_angle({0, 0, 1}, 180);
  EXPECT_EQ(world_up_for(upside_down), glm::dvec3(0, -1, 0));
}

TEST(Navigation, FlyLookKeepsTheRightVectorHorizontal) {
  const glm::dvec3 z(0, 0, 1);
  CameraSpec c = course_camera();
  // Rolled 10° about the view axis (the camera's z); the first look levels it, and no roll
  // comes back.
  c.rotation = c.rotation * rotation_axis_angle({0, 0, 1}, 10);
  EXPECT_GT(std::abs(dot(camera_right(c), z)), 0.1);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-30, 30);
  for (int i = 0; i < 5000; ++i) {
    c = fly_look(c, angle(rng), angle(rng), z);
    ASSERT_NEAR(dot(camera_right(c), z), 0.0, 1e-12) << "step " << i;
    ASSERT_GT(dot(camera_up(c), z), 0.0) << "upside down at step " << i;
    ASSERT_LE(std::asin(std::abs(dot(camera_forward(c), z))) * 180 / M_PI, kMaxPitchDegrees + 1e-9);
  }
  expect_rotation(c.rotation, 1e-12);
  EXPECT_EQ(c.eye, course_camera().eye);  // looking does not move
}

TEST(Navigation, YawTurnsLeftAndPitchLooksUp) {
  const glm::dvec3 z(0, 0, 1);
  CameraSpec c;
  c.rotation = level_rotation({1, 0, 0}, z);  // looking along +x, Z up
  CameraSpec left = fly_look(c, 90, 0, z);
  EXPECT_NEAR(length(camera_forward(left) - glm::dvec3(0, 1, 0)), 0, 1e-15);
  CameraSpec up = fly_look(c, 0, 30, z);
  EXPECT_NEAR(dot(camera_forward(up), z), 0.5, 1e-15);
  CameraSpec top = fly_look(c, 0, 120, z);  // clamped
  EXPECT_NEAR(std::asin(dot(camera_forward(top), z)) * 180 / M_PI, kMaxPitchDegrees, 1e-9);
}

TEST(Navigation, FlyLookFromStraightDownTurnsTowardTheImageTop) {
  const glm::dvec3 z(0, 0, 1);
  CameraSpec c;  // identity looks down −z with +y up: straight down in a Z-up world
  CameraSpec tipped = fly_look(c, 0, 10, z);
  // From −90° to −80°, toward +y, the image's top.
  EXPECT_NEAR(camera_forward(tipped).y, std::cos(80 * M_PI / 180), 1e-15);
  EXPECT_NEAR(camera_forward(tipped).z, -std::sin(80 * M_PI / 180), 1e-15);
  EXPECT_NEAR(dot(camera_right(tipped), z), 0.0, 1e-15);
}

TEST(Navigation, FlyMoveFollowsTheCameraFrame) {
  const glm::dvec3 z(0, 0, 1);
  CameraSpec c = course_camera();
  CameraSpec moved = fly_move(c, {0, 0, 2}, z);
  EXPECT_NEAR(length(moved.eye - (c.eye + camera_forward(c) * 2.0)), 0, 1e-14);
  EXPECT_EQ(max_difference(moved.rotation, c.rotation), 0.0);
  moved = fly_move(c, {1, 3, 0}, z);
  EXPECT_NEAR(length(moved.eye - (c.eye + camera_right(c) + z * 3.0)), 0, 1e-14);
}

TEST(Navigation, OrbitKeepsTheDistanceAndLooksAtThePivot) {
  const glm::dvec3 z(0, 0, 1);
  const glm::dvec3 pivot(0.3, -0.2, 0.5);
  CameraSpec c = course_camera();
  double d0 = length(c.eye - pivot);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> angle(-40, 40);
  for (int i = 0; i < 2000; ++i) {
    c = orbit(c, pivot, angle(rng), angle(rng), z);
    ASSERT_NEAR(length(c.eye - pivot), d0, 1e-12 * d0) << "step " << i;
    glm::dvec3 to_pivot = normalize(pivot - c.eye);
    ASSERT_NEAR(dot(camera_forward(c), to_pivot), 1.0, 1e-14);
    ASSERT_NEAR(dot(camera_right(c), z), 0.0, 1e-12);
  }
  expect_rotation(c.rotation, 1e-12);
}

TEST(Navigation, ZoomStaysWithinTheLimits) {
  EXPECT_NEAR(vertical_fov_degrees(zoom_ry(1.0, 0.5)), 45, 1e-12);  // ry 1 is 90°
  EXPECT_NEAR(vertical_fov_degrees(zoom_ry(1.0, 100)), kMaxFovDegrees, 1e-9);
  EXPECT_NEAR(vertical_fov_degrees(zoom_ry(1.0, 1e-6)), kMinFovDegrees, 1e-9);
}

// The camera as the parser reads the printed line back.
CameraSpec parsed_camera(const std::string& line) {
  ParsedScene p = parse_scene(line + "\n", testing::temp_dir() + "/nav.scn");
  EXPECT_TRUE(p.ok()) << line;
  return p.scene.camera.value_or(CameraSpec{});
}

TEST(Navigation, PrintedCameraLineParsesBackToTheSameCamera) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coord(-1e3, 1e3);
  std::vector<CameraSpec> cameras = {course_camera(), CameraSpec{}};
  for (int i = 0; i < 300; ++i) {
    glm::dquat q = random_unit_quaternion(rng);
    CameraSpec c;
    c.eye = {coord(rng), coord(rng), coord(rng) * 1e-7};
    c.ry = std::exp(coord(rng) * 1e-3);
    c.rotation = glm::mat3_cast(glm::dquat(q.w, q.x, q.y, q.z));
    cameras.push_back(c);
    cameras.push_back(fly_look(c, coord(rng), coord(rng), {0, 0, 1}));
  }
  for (const CameraSpec& c : cameras) {
    std::string line = camera_line(c);
    CameraSpec back = parsed_camera(line);
    EXPECT_EQ(back.eye, c.eye) << line;  // %.17g: the same doubles
    EXPECT_EQ(back.ry, c.ry) << line;
    EXPECT_LE(max_difference(back.rotation, c.rotation), 1e-12) << line;
  }
  EXPECT_EQ(screen_line(160, 120), "screen 160 120");
  ParsedScene s = parse_scene(screen_line(160, 120) + "\ncamera 0 0 0 1\n", "nav.scn");
  EXPECT_EQ(s.scene.width, 160u);
  EXPECT_EQ(s.scene.height, 120u);
}

}  // namespace
}  // namespace raylane
