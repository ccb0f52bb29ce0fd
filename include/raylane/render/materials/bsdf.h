// The course's reflection model at one surface point (docs/design.md, "The course's rendering
// model"): a mixture of a Lambertian lobe, a Phong-distribution microfacet reflection lobe and
// a microfacet transmission lobe, chosen by the lengths of Kd, Ks and Kt; the microfacet
// distribution is the material's (Phong, GGX or Beckman: render/materials/microfacet.h). Directions point
// away from the surface; wo is towards the viewer. eval() returns f(wo, wi)·|cos θi| and pdf()
// the density of sample() in solid angle, so value/pdf is a sample's weight; the three agree
// by construction (sample() returns eval() and pdf() of the direction it drew).
#pragma once

#include "raylane/core/vec_math.h"
#include "raylane/scene/material.h"

namespace raylane {

struct BsdfSample {
  glm::dvec3 wi{};
  glm::dvec3 value{};  // f(wo, wi)·|cos θi|; for a specular sample, the sample's weight
  double pdf = 0;      // solid-angle density; 1 for a specular sample
  // Drawn from a Dirac lobe (index-matched transmission: wi = −wo whatever the microfacet), so
  // value/pdf is the weight, and eval() and pdf() of wi are 0: light sampling cannot find it.
  bool specular = false;
  bool valid() const { return pdf > 0; }
};

struct BsdfEval {
  glm::dvec3 f{0, 0, 0};  // f(wo, wi)·|cos θi|
  double pdf = 0;         // the density sample() has of drawing wi
};

class Bsdf {
 public:
  // `ns` is the unit shading normal pointing out of the solid (or by the triangle's winding):
  // its side tells entering (wo·ns > 0: from outside, η = 1/ior) from leaving.
  Bsdf(const Material& m, const glm::dvec3& ns, const glm::dvec3& wo);

  // Both at once: they share the half vector, its lobe density and its Fresnel term.
  BsdfEval evaluate(const glm::dvec3& wi) const;
  glm::dvec3 eval(const glm::dvec3& wi) const { return evaluate(wi).f; }
  double pdf(const glm::dvec3& wi) const { return evaluate(wi).pdf; }
  // u0 picks the lobe, (u1, u2) warp the direction. An invalid sample (pdf 0) must be skipped.
  BsdfSample sample(double u0, double u1, double u2) const;

  bool black() const { return sum_ == 0; }  // no lobe at all (e.g. wo in the surface plane)

 private:
  BsdfEval evaluate_reflection(const glm::dvec3& wi, double cos_i) const;  // wi on wo's side
  glm::dvec3 reflection(const glm::dvec3& m, const glm::dvec3& wi, double d,
                        double fresnel_scale) const;
  double cos_power(const glm::dvec3& m) const;
  // D(m) and the density with which sample() draws m (Phong's warp is not D·cos θm).
  void normal_density(const glm::dvec3& m, double& d, double& pm) const;
  glm::dvec3 sample_normal(double u1, double u2) const;  // around +z
  glm::dvec3 schlick(double cos_om) const;
  double smith_g(const glm::dvec3& wi, const glm::dvec3& m) const;
  bool refracts(double cos_om) const;  // no total internal reflection through m
  bool index_matched() const;          // η_o/η_i so close to 1 that transmission is a Dirac lobe
  BsdfSample sample_index_matched(const glm::dvec3& m, double om) const;

  glm::dvec3 kd_{}, ks_{};
  double alpha_ = 0;
  Microfacet dist_ = Microfacet::kPhong;
  double alpha_g_ = 1;  // GGX's and Beckman's roughness (microfacet_alpha_g)
  glm::dvec3 n_{};      // shading normal turned to wo's side
  glm::dvec3 wo_{};     // unit
  double cos_o_ = 0;
  double eta_o_ = 1, eta_i_ = 1;  // indices on wo's side and on the other side
  double pd_ = 0, pr_ = 0, pt_ = 0, sum_ = 0;
};

// Beer's law on a ray's segment of length t that ends on a surface of material m: the course's
// exp(t·ln Kt) per channel where the segment ends on the inside of a transmissive solid, 1
// elsewhere (a material with Kt = 0 has no interior).
glm::dvec3 beer_transmittance(const Material& m, bool front_face, double t);

}  // namespace raylane
