#include "raylane/render/materials/texturing.h"

namespace raylane {

TexCoord texcoord_of(const Scene& scene, PrimRef prim, const Surface& surface) {
  return dispatch(prim.tag(), [&](auto kind) {
    using Kind = decltype(kind);
    return texcoord_ref(scene.table<Kind>(), prim.row(), surface);
  });
}

glm::dvec3 texture_factor(const Scene& scene, const Material& m, PrimRef prim,
                          const Surface& surface) {
  if (m.texture < 0) return {1, 1, 1};
  TexCoord t = texcoord_of(scene, prim, surface);
  return texture_lookup(scene.textures[m.texture].texels, t.u, t.v);
}

glm::dvec3 albedo_at(const Scene& scene, PrimRef prim, const Surface& surface) {
  const Material& m = scene.materials[scene.material_of(prim)];
  return glm::dvec3(m.kd) * texture_factor(scene, m, prim, surface);
}

}  // namespace raylane
