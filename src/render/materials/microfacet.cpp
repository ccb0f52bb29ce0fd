#include "raylane/render/materials/microfacet.h"

#include <algorithm>
#include <cmath>

#include "raylane/core/fast_math.h"
#include "raylane/core/warps.h"
#include "raylane/render/materials/microfacet_steps.h"

namespace raylane {

double microfacet_alpha_g(double alpha) {
  return std::sqrt(2 / (alpha + 2));
}

namespace {

// Walter et al. eq. 27.
double rational_g1(double a) {
  if (a >= 1.6) return 1.0;
  return (3.535 * a + 2.181 * a * a) / (1 + 2.276 * a + 2.577 * a * a);
}

glm::dvec3 around_z(double cos_t, double u2) {
  double sin_t = std::sqrt(std::max(0.0, 1 - cos_t * cos_t));
  SinCos phi = sincos_2pi(u2);
  return {sin_t * phi.cos, sin_t * phi.sin, cos_t};
}

}  // namespace

double ggx_d(double cos_m, double alpha_g) {
  return microfacet_steps::ggx_density(cos_m, alpha_g * alpha_g);
}

double beckman_d(double cos_m, double alpha_g) {
  return microfacet_steps::beckman_density(cos_m, alpha_g * alpha_g);
}

double ggx_g1(double cos_v, double cos_vm, double alpha_g) {
  return microfacet_steps::ggx_g1(cos_v, cos_vm, alpha_g * alpha_g);
}

double beckman_g1(double cos_v, double cos_vm, double alpha_g) {
  if (!(cos_vm * cos_v > 0)) return 0.0;
  double c = std::abs(cos_v), s = std::sqrt(std::max(0.0, 1 - c * c));
  if (s == 0) return 1.0;
  return rational_g1(c / (alpha_g * s));
}

glm::dvec3 sample_ggx_normal(double u1, double u2, double alpha_g) {
  return around_z(microfacet_steps::ggx_sample_cos(u1, alpha_g * alpha_g), u2);
}

glm::dvec3 sample_beckman_normal(double u1, double u2, double alpha_g) {
  return around_z(microfacet_steps::beckman_sample_cos(u1, alpha_g * alpha_g), u2);
}

}  // namespace raylane
