#include "raylane/scene/texture.h"

#include "raylane/render/materials/texel_lookup.h"

namespace raylane {

Texture make_texture(std::string file, TexelImage texels) {
  glm::dvec3 sum(0, 0, 0);
  for (uint32_t y = 0; y < texels.height; ++y)
    for (uint32_t x = 0; x < texels.width; ++x)
      sum += glm::dvec3(texels.at(x, y));
  double n = double(texels.width) * texels.height;
  glm::dvec3 mean = n > 0 ? sum / n : glm::dvec3(0, 0, 0);
  return {std::move(file), std::move(texels), mean};
}

Texture make_texture(std::string file, Image image) {
  return make_texture(std::move(file), float_texels(std::move(image)));
}

namespace {

template <class Texels>
glm::dvec3 lookup(const Texels& t, double u, double v) {
  LinearRgb<double> c = texture_texel_lookup<double>(t, u, v);
  return {c.r, c.g, c.b};
}

}  // namespace

glm::dvec3 texture_lookup(const TexelImage& texels, double u, double v) {
  return lookup(texels, u, v);
}

glm::dvec3 texture_lookup(const Image& image, double u, double v) {
  return lookup(image, u, v);
}

}  // namespace raylane
