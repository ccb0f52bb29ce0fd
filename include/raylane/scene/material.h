// Materials of the course: a reflecting `brdf` (diffuse Kd, specular Ks, Phong exponent alpha,
// transmission Kt, index of refraction) or an emitting `light` (radiance).
#pragma once

#include "raylane/core/vec3.h"

namespace raylane {

struct Material {
  Vec3f kd{0.5f, 0.5f, 0.5f};
  Vec3f ks{0.0f, 0.0f, 0.0f};
  Vec3f kt{0.0f, 0.0f, 0.0f};
  float alpha = 0.0f;
  float ior = 1.0f;
  Vec3f emission{0.0f, 0.0f, 0.0f};
  bool is_light = false;

  static Material default_grey() { return {}; }
};

}  // namespace raylane
