// The answer of a closest-hit query in double precision (reference tracers and shading).
#pragma once

#include <limits>

#include "raylane/core/prim_ref.h"
#include "raylane/prims/surface.h"

namespace raylane {

struct Hit {
  double t = std::numeric_limits<double>::infinity();
  PrimRef prim = PrimRef::invalid();
  Surface surface;          // valid only when hit()
  bool front_face = false;  // dot(ray.d, surface.ng) < 0
  bool hit() const { return prim.valid(); }
};

}  // namespace raylane
