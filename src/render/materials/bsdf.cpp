#include "raylane/render/materials/bsdf.h"

#include <cmath>

#include "raylane/render/materials/bsdf_steps.h"
#include "raylane/render/materials/microfacet.h"
#include "raylane/render/samplers/sampling.h"

namespace raylane {

namespace {

glm::dvec3 reflect(const glm::dvec3& wo, const glm::dvec3& m) {
  return 2 * dot(wo, m) * m - wo;
}

// The Phong lobe's Smith G1 (render/materials/bsdf_steps.h).
double g1(double cos_v, double cos_vm, double alpha) {
  return bsdf_steps::rational_smith_g1(cos_v, cos_vm, std::sqrt(0.5 * alpha + 1));
}

}  // namespace

Bsdf::Bsdf(const Material& m, const glm::dvec3& ns, const glm::dvec3& wo)
    : kd_(m.kd), ks_(m.ks), alpha_(m.alpha), dist_(m.microfacet), wo_(wo) {
  if (dist_ != Microfacet::kPhong) alpha_g_ = microfacet_alpha_g(alpha_);
  double c = dot(ns, wo);
  if (c == 0 || !std::isfinite(c)) return;  // sum_ = 0: black
  bool entering = c > 0;
  n_ = entering ? ns : -ns;
  cos_o_ = std::abs(c);
  eta_o_ = entering ? 1.0 : double(m.ior);
  eta_i_ = entering ? double(m.ior) : 1.0;
  pd_ = length(glm::dvec3(m.kd));
  pr_ = length(glm::dvec3(m.ks));
  pt_ = length(glm::dvec3(m.kt));
  sum_ = pd_ + pr_ + pt_;
  if (sum_ > 0) pd_ /= sum_, pr_ /= sum_, pt_ /= sum_;
}

glm::dvec3 Bsdf::schlick(double cos_om) const {
  return ks_ + (glm::dvec3(1, 1, 1) - ks_) * bsdf_steps::schlick_weight(cos_om);
}

double Bsdf::smith_g(const glm::dvec3& wi, const glm::dvec3& m) const {
  double ci = dot(wi, n_), im = dot(wi, m), om = dot(wo_, m);
  switch (dist_) {
    case Microfacet::kGgx:
      return ggx_g1(ci, im, alpha_g_) * ggx_g1(cos_o_, om, alpha_g_);
    case Microfacet::kBeckman:
      return beckman_g1(ci, im, alpha_g_) * beckman_g1(cos_o_, om, alpha_g_);
    case Microfacet::kPhong:
      break;
  }
  return g1(ci, im, alpha_) * g1(cos_o_, om, alpha_);
}

void Bsdf::normal_density(const glm::dvec3& m, double& d, double& pm) const {
  if (dist_ == Microfacet::kPhong) {
    double cp = cos_power(m);
    d = phong_d_scale(alpha_) * cp, pm = phong_normal_pdf_scale(alpha_) * cp;
    return;
  }
  double c = dot(m, n_);
  d = dist_ == Microfacet::kGgx ? ggx_d(c, alpha_g_) : beckman_d(c, alpha_g_);
  pm = c > 0 ? d * c : 0.0;  // Walter eq. 24: p(m) = D(m)·|m·n|
}

glm::dvec3 Bsdf::sample_normal(double u1, double u2) const {
  switch (dist_) {
    case Microfacet::kGgx:
      return sample_ggx_normal(u1, u2, alpha_g_);
    case Microfacet::kBeckman:
      return sample_beckman_normal(u1, u2, alpha_g_);
    case Microfacet::kPhong:
      break;
  }
  return sample_phong_normal(u1, u2, alpha_);
}

// At η = 1 a refracted ray leaves along −wo through every microfacet: the transmission lobe
// is a Dirac delta, its generalised half vector −(η_o·wo + η_i·wi) is 0 and the Jacobian of
// Walter et al.'s eq. 17 divides by 0. Near η = 1 the lobe's width is |1 − η|·tan θm, below
// what light sampling can hit and above what double keeps well: within this relative contrast
// the lobe is taken as the delta (a direction off by at most 1e-5·tan θm).
constexpr double kIndexMatchedContrast = 1e-5;

bool Bsdf::index_matched() const {
  return std::abs(eta_o_ / eta_i_ - 1) <= kIndexMatchedContrast;
}

// Transmission through microfacet m at η = 1: wi = −wo. The weight is the limit of the
// regular estimator eval/pdf as η → 1 (its 1/den² factors cancel): (1 − F)·G·(wo·m)/cos θo ·
// D/p(m) / p_t, with D/p(m) = (α+2)/(α+1) for the course's warp. Its expectation over m is the
// transmitted fraction: at normal incidence with F = 0 exactly 1 (E[cos θm] = (α+1)/(α+2)).
// GGX's and Beckman's warps have p(m) = D(m)·cos θm, so D/p(m) = 1/cos θm there.
BsdfSample Bsdf::sample_index_matched(const glm::dvec3& m, double om) const {
  BsdfSample s;
  s.wi = -wo_;
  double weight = smith_g(s.wi, m) * om / cos_o_;
  weight = dist_ == Microfacet::kPhong ? weight * (alpha_ + 2) / (alpha_ + 1) / pt_
                                       : weight / dot(m, n_) / pt_;
  s.value = (glm::dvec3(1, 1, 1) - schlick(om)) * weight;
  s.pdf = 1;
  s.specular = true;
  if (!is_finite(s.value)) s.pdf = 0;
  return s;
}

bool Bsdf::refracts(double cos_om) const {
  double eta = eta_o_ / eta_i_;
  return 1 - eta * eta * (1 - cos_om * cos_om) >= 0;
}

// D·G·F/(4|cos θi||cos θo|)·|cos θi| for microfacet density d, with F scaled per channel by
// fresnel_scale's choice: +1 gives F (the reflection lobe), −1 gives 1 − F (light the
// transmission lobe would have refracted, reflected instead by total internal reflection, so
// the two lobes sum to one).
glm::dvec3 Bsdf::reflection(const glm::dvec3& m, const glm::dvec3& wi, double d,
                            double fresnel_scale) const {
  if (d == 0) return {0, 0, 0};
  glm::dvec3 f = schlick(dot(wo_, m));
  if (fresnel_scale < 0) f = glm::dvec3(1, 1, 1) - f;
  return f * (d * smith_g(wi, m) / (4 * cos_o_));
}

// cos^α θm, shared by D(m) and the warp's density of m (sampling.h): one pow per evaluation.
double Bsdf::cos_power(const glm::dvec3& m) const {
  double c = dot(m, n_);
  return c > 0 ? std::pow(c, alpha_) : 0.0;
}

BsdfEval Bsdf::evaluate(const glm::dvec3& wi) const {
  BsdfEval out;
  if (sum_ == 0) return out;
  double cos_i = dot(wi, n_);
  if (cos_i > 0) return evaluate_reflection(wi, cos_i);
  if (!(cos_i < 0) || pt_ == 0 || index_matched()) return out;
  // Walter et al. 2007, eqs. 16 and 21: the generalised half vector and the BTDF, radiance
  // scaled by η_o² (the viewer's side).
  glm::dvec3 m = -(wo_ * eta_o_ + wi * eta_i_);
  double len = length(m);
  if (!(len > 0)) return out;
  m = m / len;
  if (dot(m, n_) < 0) m = -m;
  double om = dot(wo_, m), im = dot(wi, m);
  if (!(om > 0 && im < 0) || !refracts(om)) return out;
  double den = eta_o_ * om + eta_i_ * im;
  if (den == 0) return out;
  double d, pm;
  normal_density(m, d, pm);
  if (d > 0) {
    double s = d * smith_g(wi, m) * std::abs(im) * om * eta_o_ * eta_o_ / (cos_o_ * den * den);
    out.f = (glm::dvec3(1, 1, 1) - schlick(om)) * s;
  }
  out.pdf = pt_ * pm * eta_i_ * eta_i_ * std::abs(im) / (den * den);  // Walter eq. 17
  return out;
}

BsdfEval Bsdf::evaluate_reflection(const glm::dvec3& wi, double cos_i) const {
  BsdfEval out;
  if (pd_ > 0) out.f = kd_ * (cos_i / kPi);
  out.pdf = pd_ * cos_i / kPi;
  if (pr_ == 0 && pt_ == 0) return out;
  glm::dvec3 m = normalize(wi + wo_);
  double d, pm;
  normal_density(m, d, pm);
  bool reflects_transmission = pt_ > 0 && !refracts(dot(wo_, m));  // total internal reflection
  if (pr_ > 0) out.f += reflection(m, wi, d, 1);
  if (reflects_transmission) out.f += reflection(m, wi, d, -1);
  double im = dot(wi, m);
  double lobe = pm > 0 && im > 0 ? pm / (4 * im) : 0.0;  // Walter eq. 14
  double w = pr_ + (reflects_transmission ? pt_ : 0.0);
  out.pdf += w * lobe;  // the warp's density of m, Jacobian 1/(4|wi·m|)
  return out;
}

BsdfSample Bsdf::sample(double u0, double u1, double u2) const {
  BsdfSample s;
  if (sum_ == 0) return s;
  Frame frame(n_);
  if (u0 < pd_) {
    s.wi = frame.to_world(sample_cosine_hemisphere(u1, u2));
  } else {
    glm::dvec3 m = frame.to_world(sample_normal(u1, u2));
    double om = dot(wo_, m);
    if (!(om > 0)) return s;
    s.wi = reflect(wo_, m);
    if (u0 >= pd_ + pr_ && index_matched()) return sample_index_matched(m, om);
    if (u0 >= pd_ + pr_ && refracts(om)) {
      // Refraction through m (Walter eq. 40), η = η_o/η_i.
      double eta = eta_o_ / eta_i_;
      double k = 1 - eta * eta * (1 - om * om);
      s.wi = m * (eta * om - std::sqrt(k)) - wo_ * eta;
      if (!(dot(s.wi, n_) < 0)) return s;
    } else if (!(dot(s.wi, n_) > 0)) {
      return s;  // reflected below the horizon: absorbed, never another lobe's direction
    }
  }
  double len = length(s.wi);
  if (!(len > 0) || !std::isfinite(len)) return s;
  s.wi = s.wi / len;
  BsdfEval e = evaluate(s.wi);
  if (!(e.pdf > 0) || !std::isfinite(e.pdf)) return s;
  s.pdf = e.pdf;
  s.value = e.f;
  return s;
}

glm::dvec3 beer_transmittance(const Material& m, bool front_face, double t) {
  glm::dvec3 kt(m.kt);
  if (front_face || kt == glm::dvec3(0, 0, 0)) return {1, 1, 1};
  glm::dvec3 a{};
  for (int k = 0; k < 3; ++k)
    a[k] = kt[k] > 0 ? std::exp(t * std::log(kt[k])) : 0.0;
  return a;
}

}  // namespace raylane
