// Materials of the course: a reflecting `brdf` (diffuse Kd, specular Ks, Phong exponent alpha,
// transmission Kt, index of refraction) or an emitting `light` (radiance), either one optionally
// textured: the image multiplies Kd, or the radiance.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "raylane/core/vec_math.h"

namespace raylane {

// The distribution of a material's microfacet normals, for its reflection and transmission
// lobes (the `microfacet` command): the course's Phong distribution, or GGX or Beckman at the
// course's equivalent roughness α_g = √(2/(α + 2)) (render/materials/microfacet.h).
enum class Microfacet : uint8_t { kPhong = 0, kGgx = 1, kBeckman = 2 };
// The command's names: "phong", "ggx", "beckman".
std::optional<Microfacet> microfacet_named(std::string_view name);
const char* microfacet_name(Microfacet m);

struct Material {
  glm::vec3 kd{0.5f, 0.5f, 0.5f};
  glm::vec3 ks{0.0f, 0.0f, 0.0f};
  glm::vec3 kt{0.0f, 0.0f, 0.0f};
  float alpha = 0.0f;
  float ior = 1.0f;
  glm::vec3 emission{0.0f, 0.0f, 0.0f};
  bool is_light = false;
  Microfacet microfacet = Microfacet::kPhong;
  int32_t texture = -1;  // index into Scene::textures, or none
  // A mesh file's own texture makes a copy of the `mesh` line's material for its triangles;
  // the copy keeps the index of that material (-1 for a material of the scene file), and
  // takes that material's `texture` instead if it has one by the end of the file.
  int32_t mesh_copy_of = -1;

  static Material default_grey() { return {}; }
};

}  // namespace raylane
