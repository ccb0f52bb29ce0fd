#include "raylane/core/warps.h"

#include <algorithm>
#include <cmath>

namespace raylane {

Frame::Frame(const Vec3d& normal) : n(normal) {
  double sign = std::copysign(1.0, n.z);
  double a = -1.0 / (sign + n.z);
  double b = n.x * n.y * a;
  s = {1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
  t = {b, sign + n.y * n.y * a, -n.y};
}

Vec3d sample_cosine_hemisphere(double u1, double u2) {
  double r = std::sqrt(u1), phi = 2 * kPi * u2;
  double z = std::sqrt(std::max(0.0, 1 - u1));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3d sample_uniform_cone(double u1, double u2, double one_minus_cos_max) {
  // 1 − cos θ = u1·(1 − cos θmax) and sin²θ = (1 − cos θ)(1 + cos θ): no cancellation.
  double one_minus_cos = u1 * one_minus_cos_max;
  double cos_t = 1 - one_minus_cos;
  double sin_t = std::sqrt(std::max(0.0, one_minus_cos * (2 - one_minus_cos)));
  double phi = 2 * kPi * u2;
  return {sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t};
}

Vec3d sample_uniform_sphere(double u1, double u2) {
  double z = 1 - 2 * u1;
  double r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

}  // namespace raylane
