// Environment images for the environment light's tests (environment_test.cpp,
// environment_sampling_test.cpp): a peaked map (a small sun over a dim sky) and a smooth one.
#pragma once

#include <cmath>
#include <functional>

#include "raylane/core/warps.h"
#include "raylane/image/image.h"

namespace raylane::testing {

inline Image make_image(uint32_t w, uint32_t h,
                        const std::function<glm::vec3(uint32_t, uint32_t)>& f) {
  Image img(w, h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      img.set(x, y, f(x, y));
  return img;
}

// 64×32: a dim bluish sky brightening toward the horizon, a black ground below it, and a sun
// of 2×2 texels at columns 40–41, rows 9–10 (θ ≈ 53°) of radiance `sun` per texel.
inline Image sun_map(float sun) {
  return make_image(64, 32, [sun](uint32_t x, uint32_t y) {
    if (x >= 40 && x <= 41 && y >= 9 && y <= 10) return glm::vec3(sun, 0.9f * sun, 0.8f * sun);
    if (y >= 16) return glm::vec3(0, 0, 0);
    float t = float(y) / 16;
    return glm::vec3(0.2f + 0.3f * t, 0.3f + 0.3f * t, 0.6f + 0.2f * t);
  });
}

// 48×24: smooth in both directions, nowhere black.
inline Image gradient_map() {
  return make_image(48, 24, [](uint32_t x, uint32_t y) {
    double phi = 2 * kPi * (x + 0.5) / 48, theta = kPi * (y + 0.5) / 24;
    float a = float(1.5 + std::cos(phi)), b = float(1.2 + std::cos(theta));
    return glm::vec3(a * b, 0.5f * a, b);
  });
}

// The image-space direction of image point (u, v): φ = 2πu, θ = πv.
inline glm::dvec3 direction_of(double u, double v) {
  double phi = 2 * kPi * u, theta = kPi * v;
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

}  // namespace raylane::testing
