// The pinhole camera of the course (docs/scene-language.md, "Camera and image orientation").
#pragma once

#include <cstdint>

#include "raylane/core/numbers.h"
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

// The pinhole camera's steps, written once over the number type: N = double for the scalar
// camera (ray_through, ray_through_lens), N = double lanes for the camera's lanes
// (src/render/camera/camera_lanes_impl.h); V3 = glm::dvec3 or simd::DoubleVec3. The build has
// -ffp-contract=off, so the same steps in the same order agree bit for bit.

// The direction, not normalised, from the eye through the pixel-grid point (x, y):
// right·(sx·rx) + up·(sy·ry) + forward, with sx = 2x/W − 1 and sy = 2y/H − 1, summed left to
// right per axis as GLM's vector sums.
template <class N, class V3>
V3 pinhole_offset(const Camera& c, const N& x, const N& y) {
  const N two(2.0), one(1.0);
  const N sx = two * x / N(double(c.width)) - one, sy = two * y / N(double(c.height)) - one;
  const N a = sx * N(c.rx), b = sy * N(c.ry);
  return V3{N(c.right.x) * a + N(c.up.x) * b + N(c.forward.x),
            N(c.right.y) * a + N(c.up.y) * b + N(c.forward.y),
            N(c.right.z) * a + N(c.up.z) * b + N(c.forward.z)};
}

// The unit direction of the pinhole ray through (x, y): pinhole_offset / sqrt((dx² + dy²) +
// dz²), as core/vec_math.h's normalize, with Num<N>'s correctly rounded square root.
template <class N, class V3>
V3 pinhole_direction(const Camera& c, const N& x, const N& y) {
  const V3 d = pinhole_offset<N, V3>(c, x, y);
  const N len = Num<N>::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  return V3{d.x / len, d.y / len, d.z / len};
}

inline Rayd Camera::ray_through(double x, double y) const {
  return {eye, pinhole_direction<double, glm::dvec3>(*this, x, y)};
}

}  // namespace raylane
