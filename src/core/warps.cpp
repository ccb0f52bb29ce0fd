#include "raylane/core/warps.h"

#include <algorithm>
#include <cmath>

#include "raylane/core/fast_math.h"

namespace raylane {

Frame::Frame(const glm::dvec3& normal) : n(normal) {
  double sign = std::copysign(1.0, n.z);
  double a = -1.0 / (sign + n.z);
  double b = n.x * n.y * a;
  s = {1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
  t = {b, sign + n.y * n.y * a, -n.y};
}

glm::dvec3 sample_cosine_hemisphere(double u1, double u2) {
  double r = std::sqrt(u1);
  double z = std::sqrt(std::max(0.0, 1 - u1));
  SinCos phi = sincos_2pi(u2);
  return {r * phi.cos, r * phi.sin, z};
}

glm::dvec3 sample_concentric_disc(double u1, double u2) {
  double a = 2 * u1 - 1, b = 2 * u2 - 1;
  if (a == 0 && b == 0) return {0, 0, 0};
  // The larger of |a|, |b| is the radius; the other gives the angle within its eighth of the
  // ring, π/4·(small/large), measured from the large one's axis.
  double r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a, phi = kPi / 4 * (b / a);
  } else {
    r = b, phi = kPi / 2 - kPi / 4 * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi), 0};
}

glm::dvec3 sample_uniform_sphere(double u1, double u2) {
  double z = 1 - 2 * u1;
  double r = std::sqrt(std::max(0.0, 1 - z * z));
  SinCos phi = sincos_2pi(u2);
  return {r * phi.cos, r * phi.sin, z};
}

}  // namespace raylane
