#include "raylane/core/mat3.h"

#include <numbers>

namespace raylane {

Mat3d rotation_axis_angle(const Vec3d& u, double degrees) {
  double a = degrees * std::numbers::pi / 180.0;
  double c = std::cos(a), s = std::sin(a), t = 1.0 - c;
  Mat3d m;
  m.m[0][0] = c + u.x * u.x * t;
  m.m[0][1] = u.x * u.y * t - u.z * s;
  m.m[0][2] = u.x * u.z * t + u.y * s;
  m.m[1][0] = u.y * u.x * t + u.z * s;
  m.m[1][1] = c + u.y * u.y * t;
  m.m[1][2] = u.y * u.z * t - u.x * s;
  m.m[2][0] = u.z * u.x * t - u.y * s;
  m.m[2][1] = u.z * u.y * t + u.x * s;
  m.m[2][2] = c + u.z * u.z * t;
  return m;
}

Mat3d rotation_quaternion(double w, double x, double y, double z) {
  Mat3d m;
  m.m[0][0] = 1 - 2 * (y * y + z * z);
  m.m[0][1] = 2 * (x * y - w * z);
  m.m[0][2] = 2 * (x * z + w * y);
  m.m[1][0] = 2 * (x * y + w * z);
  m.m[1][1] = 1 - 2 * (x * x + z * z);
  m.m[1][2] = 2 * (y * z - w * x);
  m.m[2][0] = 2 * (x * z - w * y);
  m.m[2][1] = 2 * (y * z + w * x);
  m.m[2][2] = 1 - 2 * (x * x + y * y);
  return m;
}

}  // namespace raylane
