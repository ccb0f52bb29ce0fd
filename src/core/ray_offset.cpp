#include "raylane/core/ray_offset.h"

#include <cmath>

#include "raylane/core/float_util.h"

namespace raylane {

Vec3d offset_ray_origin(const Vec3d& p, const Vec3d& p_error, const Vec3d& ng,
                        const Vec3d& toward) {
  Vec3d offset = ng * dot(abs(ng), p_error);
  if (dot(ng, toward) < 0) offset = -offset;
  Vec3d o = p + offset;
  // Round away from p so the offset is not lost to rounding (pbrt-v4 OffsetRayOrigin).
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0) o[i] = next_double_up(o[i]);
    if (offset[i] < 0) o[i] = next_double_down(o[i]);
  }
  return o;
}

Vec3d hit_point_error(const Rayd& ray, double t) {
  constexpr double kBound = 32 * kFloatUnitRoundoff;
  return (abs(ray.o) + abs(ray.d * t)) * kBound;
}

}  // namespace raylane
