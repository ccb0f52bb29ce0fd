#include "raylane/scene/texture.h"

#include <cmath>

namespace raylane {

Texture make_texture(std::string file, Image image) {
  glm::dvec3 sum(0, 0, 0);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      sum += glm::dvec3(image.at(x, y));
  double n = double(image.width) * image.height;
  glm::dvec3 mean = n > 0 ? sum / n : glm::dvec3(0, 0, 0);
  return {std::move(file), std::move(image), mean};
}

namespace {

// Texel coordinate c (in texels, centres at k + 0.5) → the two texels around it and the weight of
// the second, wrapping around `size`.
struct Span {
  uint32_t a, b;
  double w;
};
Span span(double c, uint32_t size) {
  double x = c - 0.5;
  double f = std::floor(x);
  double w = x - f;
  // Repeat: f mod size in [0, size). Large |c| from far-off UVs loses fraction bits, never range.
  double m = f - std::floor(f / size) * size;
  uint32_t a = m >= 0 && m < size ? uint32_t(m) : 0;
  return {a, a + 1 == size ? 0 : a + 1, w};
}

}  // namespace

glm::dvec3 texture_lookup(const Image& image, double u, double v) {
  if (image.width == 0 || image.height == 0 || !std::isfinite(u) || !std::isfinite(v))
    return {0, 0, 0};
  u -= std::floor(u);
  v -= std::floor(v);
  Span sx = span(u * image.width, image.width);
  // Rows from the bottom: v = 0 is the file's last row.
  Span sy = span(v * image.height, image.height);
  auto texel = [&](uint32_t x, uint32_t y_up) {
    return glm::dvec3(image.at(x, image.height - 1 - y_up));
  };
  glm::dvec3 bottom = texel(sx.a, sy.a) * (1 - sx.w) + texel(sx.b, sy.a) * sx.w;
  glm::dvec3 top = texel(sx.a, sy.b) * (1 - sx.w) + texel(sx.b, sy.b) * sx.w;
  return bottom * (1 - sy.w) + top * sy.w;
}

}  // namespace raylane
