// The pinhole's rays in double lanes (render/camera/camera_lanes.h) against Camera::ray_through
// rounded to float, bit for bit at every instruction set this CPU has: random cameras
// (orientations, fields of view, odd image sizes), random pixel points, counts that are not a
// multiple of any lane width, and points on the image's edges and corners.
#include "raylane/render/camera/camera_lanes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "raylane/core/strings.h"
#include "raylane/core/warps.h"
#include "raylane/render/samplers/rng.h"
#include "support/same_bits.h"

namespace raylane {
namespace {

using testing::same_bits;

// A camera with a random orthonormal frame (right, up, forward) at a random eye.
Camera random_camera(Rng& rng) {
  Camera c;
  c.eye = sample_uniform_sphere(rng.uniform(), rng.uniform()) * (1 + 100 * rng.uniform());
  glm::dvec3 f = sample_uniform_sphere(rng.uniform(), rng.uniform());
  glm::dvec3 helper = std::abs(f.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  c.right = normalize(cross(f, helper));
  c.up = cross(c.right, f);
  c.forward = f;
  c.width = 1 + uint32_t(rng.uniform() * 700);
  c.height = 1 + uint32_t(rng.uniform() * 500);
  c.ry = std::tan(0.01 + 1.5 * rng.uniform());
  c.rx = c.ry * double(c.width) / double(c.height);
  return c;
}

struct Points {
  std::vector<double> x, y, jx, jy;
  PixelPoints view() const { return {x.data(), y.data(), jx.data(), jy.data(), x.size()}; }
};

// n points: pixel corners anywhere in the image, jitters in [0, 1); the first four are the
// image's corners with jitters 0 and the largest double below 1.
Points random_points(Rng& rng, const Camera& c, std::size_t n) {
  Points p;
  const double below_one = std::nextafter(1.0, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double x = std::floor(rng.uniform() * c.width), y = std::floor(rng.uniform() * c.height);
    double jx = rng.uniform(), jy = rng.uniform();
    if (i < 4) {
      x = (i & 1) ? c.width - 1 : 0, y = (i & 2) ? c.height - 1 : 0;
      jx = jy = (i & 1) ? below_one : 0.0;
    }
    p.x.push_back(x), p.y.push_back(y), p.jx.push_back(jx), p.jy.push_back(jy);
  }
  return p;
}

TEST(CameraLanes, PinholeRaysAreRayThroughsBitForBitAtEveryIsa) {
  for (Isa isa : supported_isas()) {
    Rng rng(7);
    std::size_t checked = 0;
    for (int cam_index = 0; cam_index < 40; ++cam_index) {
      const Camera c = random_camera(rng);
      const std::size_t n = 1 + std::size_t(rng.uniform() * 300);  // any count, tails too
      const Points pts = random_points(rng, c, n);
      RayStream out;
      out.resize(n);
      pinhole_rays(isa, c, pts.view(), out);
      for (std::size_t i = 0; i < n; ++i, ++checked) {
        const Rayf want =
            ray_cast<float>(c.ray_through(pts.x[i] + pts.jx[i], pts.y[i] + pts.jy[i]));
        const Rayf got = out.get(i);
        ASSERT_TRUE(same_bits(got.o, want.o) && same_bits(got.d, want.d) &&
                    same_bits(got.tmin, want.tmin) && same_bits(got.tmax, want.tmax))
            << isa_name(isa) << " camera " << cam_index << " point " << i << " of " << n;
      }
    }
    EXPECT_GT(checked, 1000u) << isa_name(isa);
  }
}

}  // namespace
}  // namespace raylane
