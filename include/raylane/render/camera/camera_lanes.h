// The pinhole camera's rays for many pixel points at once, in double SIMD lanes: ray_through's
// steps in its order and precision (the build has -ffp-contract=off), each ray rounded to float
// as the render's wavefront stores it, so the lanes give Camera::ray_through's rays bit for bit
// (tests/render/camera_lanes_test.cpp). The kernel lives in the per-ISA units
// src/render/render_lanes_<isa>.cpp, picked at run time through their table
// (src/render/render_lanes.h).
#pragma once

#include <cstddef>

#include "raylane/render/camera/camera.h"
#include "raylane/simd/isa.h"
#include "raylane/trace/ray_stream.h"

namespace raylane {

// The pixel points of camera rays, as columns: point i is (x[i] + jx[i], y[i] + jy[i]) in the
// pixel grid (x right, y up from the bottom edge), the pixel's corner and its jitter.
struct PixelPoints {
  const double *x, *y, *jx, *jy;
  std::size_t size;
};

// Rays [0, points.size) of `out` (sized by the caller) are the pinhole camera's rays through the
// points, rounded to float. Contract: !cam.has_lens().
void pinhole_rays(Isa isa, const Camera& cam, const PixelPoints& points, RayStream& out);

}  // namespace raylane
