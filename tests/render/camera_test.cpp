// The camera of the course (docs/scene-language.md, "Camera and image orientation").
#include <gtest/gtest.h>

#include <algorithm>

#include "raylane/render/camera/camera.h"
#include "raylane/render/samplers/rng.h"
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
  glm::dvec3 p = r.at(t);
  EXPECT_LT(length(p), 0.36);
  EXPECT_NEAR(p.y, -0.22, 0.02);
  EXPECT_NEAR(p.z, 0.27, 0.02);
  EXPECT_GT(c.up.z, 0.0);
}

// Without a lens the thin-lens ray is the pinhole ray bit for bit; with one, every ray for a
// grid point starts on the aperture disc around the eye (in the right-up plane) and passes
// through the pinhole ray's point at `focus` along the forward axis.
TEST(Camera, ThinLensRaysMeetInThePlaneInFocus) {
  Camera c = test_scene_camera();
  Rng rng(9);
  for (int i = 0; i < 1000; ++i) {
    double x = rng.uniform() * c.width, y = rng.uniform() * c.height;
    Rayd pin = c.ray_through(x, y), lens = c.ray_through_lens(x, y, rng.uniform(), rng.uniform());
    ASSERT_TRUE(pin.o == lens.o && pin.d == lens.d);
  }
  c.lens_radius = 0.05, c.focus = 2.5;
  double widest = 0;
  for (int i = 0; i < 1000; ++i) {
    double x = rng.uniform() * c.width, y = rng.uniform() * c.height;
    Rayd pin = c.ray_through(x, y);
    Rayd r = c.ray_through_lens(x, y, rng.uniform(), rng.uniform());
    glm::dvec3 off = r.o - c.eye;
    EXPECT_LE(length(off), c.lens_radius * (1 + 1e-12));
    EXPECT_NEAR(dot(off, c.forward), 0, 1e-15);
    widest = std::max(widest, length(off));
    // Where the pinhole ray crosses the plane in focus (forward distance `focus`).
    glm::dvec3 f = pin.at(c.focus / dot(pin.d, c.forward));
    double t = dot(f - r.o, r.d);
    EXPECT_LT(length(r.at(t) - f), 1e-12 * c.focus);
    EXPECT_NEAR(length(r.d), 1, 1e-15);
  }
  EXPECT_GT(widest, 0.9 * c.lens_radius);  // the aperture is used, not just its centre
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
  glm::dvec3 z = cross(c.right, c.up);
  EXPECT_NEAR(dot(z, c.forward), -1.0, 1e-6);
}

}  // namespace
}  // namespace raylane
