// What textures do to shading: the texture coordinates of a surface point by its kind
// (prims/<kind>.h, texcoord_ref), and the factor a textured material's image puts on Kd or on
// the emitted radiance there (docs/scene-language.md, "Beyond project 4: textures, environment,
// lens").
#pragma once

#include "raylane/prims/prim_list.h"
#include "raylane/scene/scene.h"

namespace raylane {

TexCoord texcoord_of(const Scene& scene, PrimRef prim, const Surface& surface);

// The material's image at the point, or (1, 1, 1) for an untextured material.
glm::dvec3 texture_factor(const Scene& scene, const Material& m, PrimRef prim,
                          const Surface& surface);

// Kd of the primitive's material (0 on a light) times its texture at the point: what
// `--mode albedo` shows and the albedo AOV sums.
glm::dvec3 albedo_at(const Scene& scene, PrimRef prim, const Surface& surface);

}  // namespace raylane
