// Warps from the unit square to directions, with their densities (solid-angle measure), and
// the MIS weight. Every warp is total: u in [0, 1]² never gives NaN (hard-cases N6).
#pragma once

#include "raylane/core/vec3.h"

namespace raylane {

inline constexpr double kPi = 3.14159265358979323846;

// An orthonormal frame (s, t, n) around a unit vector n (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited", JCGT 6(1)): branch-free except for the sign of n.z.
struct Frame {
  Vec3d s, t, n;
  explicit Frame(const Vec3d& normal);
  Vec3d to_world(const Vec3d& v) const { return s * v.x + t * v.y + n * v.z; }
  Vec3d to_local(const Vec3d& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
};

// Cosine-weighted hemisphere around +z (Malley's method: a uniform disk point lifted up);
// pdf = cosθ/π.
Vec3d sample_cosine_hemisphere(double u1, double u2);
inline double cosine_hemisphere_pdf(double cos_theta) {
  return cos_theta > 0 ? cos_theta / kPi : 0.0;
}

// The course's Phong microfacet distribution D(m) = (α+2)/(2π)·cos^α θm for cos θm > 0.
double phong_d(double cos_theta_m, double alpha);
// A microfacet normal around +z by the course's warp cos θm = u1^(1/(α+1)). Its density is
// (α+1)/(2π)·cos^α θm (P(cos θm ≤ c) = c^(α+1)), which is NOT D(m)·cos θm: that density
// needs the exponent 1/(α+2) (Walter et al. 2007, "Microfacet Models for Refraction through
// Rough Surfaces", eq. 35). Keeping the course's warp, the pdf must be this one; pairing the
// warp with D·cos θm biases the estimate (the chi-square test in sampling_test.cpp sees it).
Vec3d sample_phong_normal(double u1, double u2, double alpha);
double phong_normal_pdf(double cos_theta_m, double alpha);

// A direction uniformly inside the cone around +z of half-angle θmax, given
// one_minus_cos_max = 1 − cos θmax (computed by the caller without cancellation for narrow
// cones); pdf = 1 / (2π·(1 − cos θmax)).
Vec3d sample_uniform_cone(double u1, double u2, double one_minus_cos_max);

// A uniform direction on the unit sphere; pdf = 1/(4π).
Vec3d sample_uniform_sphere(double u1, double u2);

// Veach's power heuristic with β = 2 (Veach 1997, thesis §9.2.4) for one sample of each.
inline double power_heuristic(double pdf_this, double pdf_other) {
  double a = pdf_this * pdf_this, b = pdf_other * pdf_other;
  return a > 0 ? a / (a + b) : 0.0;
}

}  // namespace raylane
