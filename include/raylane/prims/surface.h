// What a reference kernel reports about a hit point, computed once for the closest hit.
#pragma once

#include "raylane/core/vec3.h"

namespace raylane {

struct Surface {
  Vec3d p;   // the hit point
  Vec3d ng;  // unit geometric normal, pointing out of the solid (or by the triangle's winding)
  Vec3d ns;  // unit shading normal (interpolated for mesh triangles; = ng otherwise)
};

}  // namespace raylane
