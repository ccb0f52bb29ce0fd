#include "raylane/core/rotation.h"

#include <numbers>

namespace raylane {

glm::dmat3 rotation_axis_angle(const glm::dvec3& u, double degrees) {
  double a = degrees * std::numbers::pi / 180.0;
  double c = std::cos(a), s = std::sin(a), t = 1.0 - c;
  glm::dmat3 m{1.0};  // m[column][row], every element set below
  m[0][0] = c + u.x * u.x * t;
  m[1][0] = u.x * u.y * t - u.z * s;
  m[2][0] = u.x * u.z * t + u.y * s;
  m[0][1] = u.y * u.x * t + u.z * s;
  m[1][1] = c + u.y * u.y * t;
  m[2][1] = u.y * u.z * t - u.x * s;
  m[0][2] = u.z * u.x * t - u.y * s;
  m[1][2] = u.z * u.y * t + u.x * s;
  m[2][2] = c + u.z * u.z * t;
  return m;
}

}  // namespace raylane
