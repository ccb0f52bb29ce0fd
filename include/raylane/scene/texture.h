// Image textures (docs/scene-language.md, "Beyond project 4: textures, environment, lens"): the
// scene keeps each image once, in the compact form it was read in (image/texels.h); materials
// refer to them by index. Looked up at (u, v) with u to the right and v UP the image (v = 0 is
// the file's bottom row), repeating, bilinear between texel centres (render/materials/texel_lookup.h).
#pragma once

#include <cstdint>
#include <string>

#include "raylane/core/vec_math.h"
#include "raylane/image/image.h"
#include "raylane/image/texels.h"

namespace raylane {

struct Texture {
  std::string file;   // as found (for messages and `raylane info`)
  TexelImage texels;  // top row first; no texels when only the header was read (`info`)
  glm::dvec3 mean{};  // the average texel: what a textured emitter's power is estimated with
};

Texture make_texture(std::string file, TexelImage texels);
Texture make_texture(std::string file, Image image);

// The bilinear value at (u, v), repeating in both directions: texture_texel_lookup<double>.
glm::dvec3 texture_lookup(const TexelImage& texels, double u, double v);
glm::dvec3 texture_lookup(const Image& image, double u, double v);

}  // namespace raylane
