// A procedural closed mesh of any size: an icosahedron subdivided `levels` times (20·4^levels
// triangles, shared vertices) with its radius displaced by smooth bumps.
#pragma once

#include <cstdint>

#include "raylane/prims/triangle.h"

namespace raylane::bench {

void add_displaced_icosphere(TriangleTable& table, int levels, uint32_t material);

// The same surface at any size: each icosahedron face cut into frequency² triangles on a grid
// of barycentric points projected to the sphere (20·frequency² triangles; not the same
// vertices as `levels` subdivisions for frequency 2^levels). For the scale runs (10M
// triangles lies between 4^9 and 4^10 times 20).
void add_displaced_geodesic_sphere(TriangleTable& table, int frequency, uint32_t material);

}  // namespace raylane::bench
