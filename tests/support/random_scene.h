// Seeded scenes and rays for the BVH and packet tests.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "raylane/core/ray.h"
#include "raylane/scene/scene.h"

namespace raylane::testing {

// `n` primitives of every kind (moving spheres included), scattered in a cube of half-size `extent`
// around `offset`, with sizes around `size`. Materials: 0 grey, 1 a light (a few of the spheres use
// it).
Scene random_scene(uint32_t seed, int n, double extent = 10, double size = 0.6,
                   glm::dvec3 offset = {0, 0, 0});

// A closed mesh: a UV sphere of `rings` × `segments` with shared vertices and single-vertex
// poles, radii jittered in [1, 1.3] (docs/hard-cases.md T1), appended to `scene`.
void add_closed_uv_sphere(Scene& scene, uint32_t seed, int rings, int segments,
                          glm::dvec3 offset = {0, 0, 0});

// Rays from points in the cube of half-size `extent` around `offset` towards random points
// (unit directions, tmin 0, tmax inf), at times in the shutter interval [0, 1).
std::vector<Rayd> random_rays(uint32_t seed, int n, double extent, glm::dvec3 offset = {0, 0, 0});

// Float rays are what the packet tracer takes: round each ray's origin and direction.
Rayd round_to_float(const Rayd& r);

}  // namespace raylane::testing
