// A procedural closed mesh of any size: an icosahedron subdivided `levels` times (20·4^levels
// triangles, shared vertices) with its radius displaced by smooth bumps.
#pragma once

#include <cstdint>

#include "raylane/prims/triangle.h"

namespace raylane::bench {

void add_displaced_icosphere(TriangleTable& table, int levels, uint32_t material);

}  // namespace raylane::bench
