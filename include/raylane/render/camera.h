// The pinhole camera of the course (docs/scene-language.md, "Camera and image orientation").
#pragma once

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
  Rayd ray_through(double x, double y) const {
    double dx = 2 * x / width - 1, dy = 2 * y / height - 1;
    glm::dvec3 d = normalize(right * (dx * rx) + up * (dy * ry) + forward);
    return {eye, d};
  }

  bool has_lens() const { return lens_radius > 0; }

  // The thin lens (docs/scene-language.md, "lens"): from the point (a, b) of the aperture disc,
  // drawn from (u1, u2) by the concentric map, toward where the pinhole ray through (x, y)
  // meets the plane in focus, F = eye + focus·(dx·rx·right + dy·ry·up + forward). Without a
  // lens, ray_through(x, y) itself, bit for bit.
  Rayd ray_through_lens(double x, double y, double u1, double u2) const;
};

}  // namespace raylane
