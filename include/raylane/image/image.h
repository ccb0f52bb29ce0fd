// An RGB float image. Row 0 is the TOP row of the picture (as image files store it); the
// renderer, whose pixel grid counts y up from the bottom, flips when it stores.
#pragma once

#include <cstdint>
#include <vector>

#include "raylane/core/limits.h"
#include "raylane/core/vec_math.h"

namespace raylane {

struct Image {
  uint32_t width = 0, height = 0;
  std::vector<float> rgb;  // 3 floats per pixel, row-major, top row first

  Image() = default;
  Image(uint32_t w, uint32_t h) : width(w), height(h), rgb(std::size_t(w) * h * 3, 0.0f) {}

  std::size_t index(uint32_t x, uint32_t y) const { return (std::size_t(y) * width + x) * 3; }
  glm::vec3 at(uint32_t x, uint32_t y) const {
    std::size_t i = index(x, y);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
  void set(uint32_t x, uint32_t y, const glm::vec3& c) {
    std::size_t i = index(x, y);
    rgb[i] = c.x, rgb[i + 1] = c.y, rgb[i + 2] = c.z;
  }
};

}  // namespace raylane
