// The path tracer's own warps (the course's Phong microfacet lobe; the MIS weight is in
// render/vertex_steps.h); the
// general warps are in core/warps.h. Every warp is total: u in [0, 1]² never gives NaN
// (docs/hard-cases.md N6).
#pragma once

#include "raylane/core/warps.h"

namespace raylane {

// The course's Phong microfacet distribution D(m) = (α+2)/(2π)·cos^α θm for cos θm > 0.
double phong_d(double cos_theta_m, double alpha);
inline double phong_d_scale(double alpha) {
  return (alpha + 2) / (2 * kPi);
}
// A microfacet normal around +z by the course's warp cos θm = u1^(1/(α+1)). Its density is
// (α+1)/(2π)·cos^α θm (P(cos θm ≤ c) = c^(α+1)), which is NOT D(m)·cos θm: that density
// needs the exponent 1/(α+2) (Walter et al. 2007, "Microfacet Models for Refraction through
// Rough Surfaces", eq. 35). Keeping the course's warp, the pdf must be this one; pairing the
// warp with D·cos θm biases the estimate (the chi-square test in sampling_test.cpp sees it).
glm::dvec3 sample_phong_normal(double u1, double u2, double alpha);
double phong_normal_pdf(double cos_theta_m, double alpha);
inline double phong_normal_pdf_scale(double alpha) {
  return (alpha + 1) / (2 * kPi);
}

}  // namespace raylane
