#include "raylane/render/microfacet.h"

#include <algorithm>
#include <cmath>

#include "raylane/core/fast_math.h"
#include "raylane/core/warps.h"

namespace raylane {

double microfacet_alpha_g(double alpha) {
  return std::sqrt(2 / (alpha + 2));
}

namespace {

// tan²θ from cos θ > 0; inf where cos²θ underflows.
double tan2(double c) {
  double c2 = c * c;
  return std::max(0.0, 1 - c2) / c2;
}

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

// α_g²/(π cos⁴θm (α_g² + tan²θm)²), with cos⁴θm·(α_g² + tan²θm)² = (α_g² cos²θm + sin²θm)²
// so that a grazing m gives a finite value (α_g²/π at cos θm = 0) instead of 0·inf.
double ggx_d(double cos_m, double alpha_g) {
  if (!(cos_m > 0)) return 0.0;
  double a2 = alpha_g * alpha_g, c2 = std::min(1.0, cos_m * cos_m);
  double den = a2 * c2 + (1 - c2);
  return a2 / (kPi * den * den);
}

double beckman_d(double cos_m, double alpha_g) {
  if (!(cos_m > 0)) return 0.0;
  double a2 = alpha_g * alpha_g, e = tan2(cos_m) / a2;
  if (!(e < 700)) return 0.0;  // exp(−700) ≈ 1e-304: below any cos⁻⁴ this can divide by
  double c2 = cos_m * cos_m;
  return std::exp(-e) / (kPi * a2 * c2 * c2);
}

double ggx_g1(double cos_v, double cos_vm, double alpha_g) {
  if (!(cos_vm * cos_v > 0)) return 0.0;
  double t2 = tan2(std::abs(cos_v));
  return 2 / (1 + std::sqrt(1 + alpha_g * alpha_g * t2));
}

double beckman_g1(double cos_v, double cos_vm, double alpha_g) {
  if (!(cos_vm * cos_v > 0)) return 0.0;
  double c = std::abs(cos_v), s = std::sqrt(std::max(0.0, 1 - c * c));
  if (s == 0) return 1.0;
  return rational_g1(c / (alpha_g * s));
}

// tan²θm = α_g²·u1/(1 − u1), written as cos²θm = (1 − u1)/(1 − u1 + α_g² u1): no infinity
// at u1 = 1 (m in the plane, density 0).
glm::dvec3 sample_ggx_normal(double u1, double u2, double alpha_g) {
  double a2 = alpha_g * alpha_g, rest = 1 - u1;
  double c2 = rest / (rest + a2 * u1);
  return around_z(std::sqrt(std::max(0.0, c2)), u2);
}

// tan²θm = −α_g² ln(1 − u1): cos θm = 1/√(1 + tan²θm), 0 at u1 = 1.
glm::dvec3 sample_beckman_normal(double u1, double u2, double alpha_g) {
  double t2 = -alpha_g * alpha_g * std::log1p(-std::min(u1, 1.0));
  return around_z(1 / std::sqrt(1 + t2), u2);
}

}  // namespace raylane
