// The camera of the course (docs/scene-language.md, "Camera and image orientation").
#include <gtest/gtest.h>

#include "raylane/render/camera.h"
#include "raylane/scene/parser.h"
#include "support/paths.h"

namespace raylane {
namespace {

Camera test_scene_camera() {
  auto p = load_scene_file(testing::source_path("scenes/testscene.scn"));
  EXPECT_TRUE(p.ok());
  return Camera::from_scene(p.scene);
}

// The test scene's eye looks at the table: the ray through the image centre passes within
// 0.36 of the origin, about 0.22 on the −y side and 0.27 above.
TEST(Camera, TestSceneLooksAtTheTable) {
  Camera c = test_scene_camera();
  Rayd r = c.ray_through(c.width / 2.0, c.height / 2.0);
  double t = -dot(r.o, r.d);  // closest approach to the origin (|d| = 1)
  Vec3d p = r.at(t);
  EXPECT_LT(length(p), 0.36);
  EXPECT_NEAR(p.y, -0.22, 0.02);
  EXPECT_NEAR(p.z, 0.27, 0.02);
  EXPECT_GT(c.up.z, 0.0);
}

TEST(Camera, FrameIsOrthonormalAndFieldOfViewMatchesRy) {
  Camera c = test_scene_camera();
  EXPECT_NEAR(dot(c.right, c.up), 0, 1e-6);
  EXPECT_NEAR(dot(c.right, c.forward), 0, 1e-6);
  EXPECT_NEAR(length(c.forward), 1, 1e-6);
  EXPECT_DOUBLE_EQ(c.rx, 0.2 * 400 / 300);
  // The top edge's centre ray makes an angle atan(ry) with forward.
  Rayd top = c.ray_through(c.width / 2.0, c.height);
  EXPECT_NEAR(dot(top.d, c.forward), std::cos(std::atan(c.ry)), 1e-12);
}

// y counts up from the bottom: the ray through the top row points more along `up`, and the
// ray through the right column more along `right`.
TEST(Camera, PixelGridIsUprightAndNotMirrored) {
  Camera c = test_scene_camera();
  Rayd top = c.ray_through(c.width / 2.0, c.height - 0.5);
  Rayd bottom = c.ray_through(c.width / 2.0, 0.5);
  EXPECT_GT(dot(top.d, c.up), dot(bottom.d, c.up));
  EXPECT_GT(dot(c.ray_through(c.width - 0.5, c.height / 2.0).d, c.right), 0);
  EXPECT_LT(dot(c.ray_through(0.5, c.height / 2.0).d, c.right), 0);
  // Right-handed frame: right × up = −forward... R maps x × y = z, and forward = −z.
  Vec3d z = cross(c.right, c.up);
  EXPECT_NEAR(dot(z, c.forward), -1.0, 1e-6);
}

}  // namespace
}  // namespace raylane
