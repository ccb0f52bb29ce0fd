// What a reference kernel reports about a hit point, computed once for the closest hit; and
// the points and directions a kind's sampling hooks return (prim_list.h).
#pragma once

#include "raylane/core/vec_math.h"

namespace raylane {

struct Surface {
  glm::dvec3 p{};  // the hit point
  glm::dvec3
      ng{};  // unit geometric normal, pointing out of the solid (or by the triangle's winding)
  glm::dvec3 ns{};  // unit shading normal (interpolated for mesh triangles; = ng otherwise)
};

// Texture coordinates (docs/scene-language.md, "Beyond project 4: textures, environment, lens"): u
// to the right, v up the image; computed per kind by texcoord_ref only where a textured material
// needs them.
struct TexCoord {
  double u = 0, v = 0;
};

// A point on a primitive's surface and its unit outward normal (by the winding for triangles).
struct AreaSample {
  glm::dvec3 p{}, n{};
};

// A direction toward a primitive from a reference point, drawn uniformly over the solid angle
// the primitive subtends there (density 1 / solid_angle), and the distance to the surface
// along it.
struct SubtendedSample {
  glm::dvec3 wi{};
  double dist = 0;
  double solid_angle = 0;
};

}  // namespace raylane
