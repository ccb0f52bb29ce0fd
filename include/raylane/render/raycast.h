// Ray-casting views: one ray per pixel centre, shaded by a mode (the course's first project).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "raylane/image/image.h"
#include "raylane/render/camera.h"
#include "raylane/render/tracer.h"
#include "raylane/scene/scene.h"

namespace raylane {

enum class RaycastMode {
  kNormal,  // (N + 1) / 2 of the shading normal
  kDepth,   // the hit distance t in every channel; 0 for a miss
  kAlbedo,  // Kd
  kId,      // (kind tag + 1, row index, 0); 0 for a miss
  kLit,     // ambient·Kd plus a Phong term from each emitting sphere's centre, shadowed
};

std::optional<RaycastMode> raycast_mode_from_name(std::string_view name);
std::string_view raycast_mode_name(RaycastMode mode);

struct RaycastStats {
  uint64_t camera_rays = 0;
  uint64_t shadow_rays = 0;
};

// Renders every pixel; camera rays go out in 4×4-pixel tiles (coherent packets), rows are
// stored top row first (Image's convention).
Image render_raycast(const Tracer& tracer, RaycastMode mode, RaycastStats* stats = nullptr);

// The origin of a ray leaving surface point p: moved along the geometric normal, to the
// side `toward` points to, by a bound on p's own rounding error (pbrt-v4 `OffsetRayOrigin`;
// Wächter and Binder, Ray Tracing Gems ch. 6), so the ray cannot re-hit the surface it starts
// on. `p_error` is a componentwise bound on |p − exact p|.
Vec3d offset_ray_origin(const Vec3d& p, const Vec3d& p_error, const Vec3d& ng, const Vec3d& toward);

// A componentwise bound on the error of a hit point o + t·d whose t came from a float
// kernel: a float t is within a few ulps, so allow 2^5 float roundoffs of |o| + |t·d|.
Vec3d hit_point_error(const Rayd& ray, double t);

}  // namespace raylane
