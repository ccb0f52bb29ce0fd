// The pinhole camera of the course (docs/scene-language.md, "Camera and image orientation").
#pragma once

#include <cmath>
#include <cstdint>

#include "raylane/core/ray.h"
#include "raylane/scene/scene.h"

namespace raylane {

struct Camera {
  glm::dvec3 eye{};
  glm::dvec3 right{}, up{}, forward{};  // R·x, R·y, R·(−z)
  double rx = 1, ry = 1;                // tan of the half fields of view; rx = ry·W/H
  uint32_t width = 1, height = 1;
  double lens_radius = 0, focus = 1;  // `lens r d` (0: the pinhole)

  // Contract: scene.camera is set (the parser guarantees it for a scene without errors).
  static Camera from_scene(const Scene& scene);

  // The unit-direction ray through the point (x, y) of the pixel grid: x counts right from
  // the left edge, y counts UP from the bottom edge; (i + 0.5, j + 0.5) is a pixel centre.
  Rayd ray_through(double x, double y) const;

  bool has_lens() const { return lens_radius > 0; }

  // The thin lens (docs/scene-language.md, "lens"): from the point (a, b) of the aperture disc,
  // drawn from (u1, u2) by the concentric map, toward where the pinhole ray through (x, y)
  // meets the plane in focus, F = eye + focus·(dx·rx·right + dy·ry·up + forward). Without a
  // lens, ray_through(x, y) itself, bit for bit.
  Rayd ray_through_lens(double x, double y, double u1, double u2) const;
};

// The unit direction of the pinhole ray through the pixel-grid point (x, y), written once over
// the number type: N = double for Camera::ray_through, N = double lanes for the camera's lanes
// (src/render/camera/camera_lanes_impl.h); V3 = glm::dvec3 or simd::DoubleVec3. The steps, in their
// order (the build has -ffp-contract=off, so both agree bit for bit): sx = 2x/W − 1,
// d = right·(sx·rx) + up·(sy·ry) + forward, d / sqrt((dx² + dy²) + dz²) as core/vec_math.h's
// normalize, with the correctly rounded square root `sqrt_of` (std::sqrt, simd::sqrt).
template <class N, class V3, class Sqrt>
V3 pinhole_direction(const Camera& c, const N& x, const N& y, Sqrt sqrt_of) {
  const N two(2.0), one(1.0);
  const N sx = two * x / N(double(c.width)) - one, sy = two * y / N(double(c.height)) - one;
  const N a = sx * N(c.rx), b = sy * N(c.ry);
  const N dx = N(c.right.x) * a + N(c.up.x) * b + N(c.forward.x);
  const N dy = N(c.right.y) * a + N(c.up.y) * b + N(c.forward.y);
  const N dz = N(c.right.z) * a + N(c.up.z) * b + N(c.forward.z);
  const N len = sqrt_of(dx * dx + dy * dy + dz * dz);
  return V3{dx / len, dy / len, dz / len};
}

inline Rayd Camera::ray_through(double x, double y) const {
  return {eye, pinhole_direction<double, glm::dvec3>(*this, x, y,
                                                     [](double v) { return std::sqrt(v); })};
}

}  // namespace raylane
