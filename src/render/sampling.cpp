#include "raylane/render/sampling.h"

#include <algorithm>
#include <cmath>

namespace raylane {

double phong_d(double cos_theta_m, double alpha) {
  if (!(cos_theta_m > 0)) return 0.0;
  return (alpha + 2) / (2 * kPi) * std::pow(cos_theta_m, alpha);
}

Vec3d sample_phong_normal(double u1, double u2, double alpha) {
  double cos_t = std::pow(u1, 1.0 / (alpha + 1));
  double sin_t = std::sqrt(std::max(0.0, 1 - cos_t * cos_t));
  double phi = 2 * kPi * u2;
  return {sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t};
}

double phong_normal_pdf(double cos_theta_m, double alpha) {
  if (!(cos_theta_m > 0)) return 0.0;
  return (alpha + 1) / (2 * kPi) * std::pow(cos_theta_m, alpha);
}

}  // namespace raylane
