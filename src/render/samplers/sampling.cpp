#include "raylane/render/samplers/sampling.h"

#include <algorithm>
#include <cmath>

#include "raylane/core/fast_math.h"

namespace raylane {

double phong_d(double cos_theta_m, double alpha) {
  if (!(cos_theta_m > 0)) return 0.0;
  return phong_d_scale(alpha) * std::pow(cos_theta_m, alpha);
}

glm::dvec3 sample_phong_normal(double u1, double u2, double alpha) {
  double cos_t = std::pow(u1, 1.0 / (alpha + 1));
  double sin_t = std::sqrt(std::max(0.0, 1 - cos_t * cos_t));
  SinCos phi = sincos_2pi(u2);
  return {sin_t * phi.cos, sin_t * phi.sin, cos_t};
}

double phong_normal_pdf(double cos_theta_m, double alpha) {
  if (!(cos_theta_m > 0)) return 0.0;
  return phong_normal_pdf_scale(alpha) * std::pow(cos_theta_m, alpha);
}

}  // namespace raylane
