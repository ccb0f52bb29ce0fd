#include "raylane/core/ray_offset.h"

#include <cmath>

#include "raylane/core/float_util.h"

namespace raylane {

glm::dvec3 offset_ray_origin(const glm::dvec3& p, const glm::dvec3& p_error, const glm::dvec3& ng,
                             const glm::dvec3& toward) {
  glm::dvec3 offset = ng * dot(abs(ng), p_error);
  if (dot(ng, toward) < 0) offset = -offset;
  glm::dvec3 o = p + offset;
  // Round away from p so the offset is not lost to rounding (pbrt-v4 OffsetRayOrigin).
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0) o[i] = next_double_up(o[i]);
    if (offset[i] < 0) o[i] = next_double_down(o[i]);
  }
  return o;
}

glm::dvec3 hit_point_error(const Rayd& ray, double t) {
  constexpr double kBound = 32 * kFloatUnitRoundoff;
  return (abs(ray.o) + abs(ray.d * t)) * kBound;
}

}  // namespace raylane
