#include "raylane/core/ray_offset.h"

#include <cmath>

#include "raylane/core/float_util.h"

namespace raylane {

glm::dvec3 offset_ray_origin(const glm::dvec3& p, const glm::dvec3& p_error, const glm::dvec3& ng,
                             const glm::dvec3& toward) {
  return offset_origin<double>(p, p_error, ng, toward);
}

glm::dvec3 hit_point_error(const Rayd& ray, double t) {
  constexpr double kBound = 32 * kFloatUnitRoundoff;
  return (abs(ray.o) + abs(ray.d * t)) * kBound;
}

}  // namespace raylane
