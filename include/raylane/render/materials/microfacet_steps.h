// GGX and Beckman (render/materials/microfacet.h) written once over the number type N (core/numbers.h):
// N = double is the reference Bsdf's (src/render/materials/microfacet.cpp), N = float lanes the lane
// BSDF's (src/render/materials/microfacet_lanes_impl.h). Branches are selects, so that lanes never
// diverge; the scalar instantiation computes the side not taken too, and discards it. a2 is
// α_g², the course's conversion of the Phong exponent (render/materials/microfacet.h). Sources: Walter,
// Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough Surfaces",
// eqs. 33, 25 (D), 34 (GGX's G1), 35 and 28 (the warps of m).
#pragma once

#include "raylane/core/numbers.h"
#include "raylane/core/warps.h"

namespace raylane::microfacet_steps {

// GGX's D(m) at c = cos θm, 0 where c ≤ 0: α_g²/(π cos⁴θm (α_g² + tan²θm)²), written as
// α_g²/(π (α_g² cos²θm + sin²θm)²) so that a grazing m gives α_g²/π instead of 0·inf.
template <class N>
N ggx_density(const N& c, const N& a2) {
  using O = Num<N>;
  const N c2 = O::min(N(1), c * c), den = a2 * c2 + (N(1) - c2);
  return O::select(c > N(0), a2 / (N(kPi) * den * den), N(0));
}

// Beckman's D(m) at c = cos θm, 0 where c ≤ 0: exp(−tan²θm/α_g²)/(π α_g² cos⁴θm), taken as 0
// where the exponent passes the type's cutoff (below it cos θm is large enough that nothing
// divides by a vanishing cos⁴).
template <class N>
N beckman_density(const N& c, const N& a2) {
  using O = Num<N>;
  const N c2 = c * c, e = O::max(N(0), N(1) - c2) / c2 / a2;
  const N d = O::exp_neg(e) / (N(kPi) * a2 * c2 * c2);
  return O::select((c > N(0)) & (e < N(O::kExpNegCutoff)), d, N(0));
}

// GGX's Smith G1 = 2/(1 + √(1 + α_g² tan²θv)); 0 for a back-facing microfacet
// ((v·m)(v·n) ≤ 0). At cos θv = 0, tan²θv = inf gives 0.
template <class N>
N ggx_g1(const N& cos_v, const N& cos_vm, const N& a2) {
  using O = Num<N>;
  const N c = O::abs(cos_v), c2 = c * c;
  const N t2 = O::max(N(0), N(1) - c2) / c2;
  return O::select(cos_vm * cos_v > N(0), N(2) / (N(1) + O::sqrt(N(1) + a2 * t2)), N(0));
}

// cos θm drawn with density D(m)·cos θm from u1 in [0, 1]. GGX: tan²θm = α_g²u1/(1 − u1),
// written as cos²θm = (1 − u1)/(1 − u1 + α_g²u1), without an infinity at u1 = 1.
template <class N>
N ggx_sample_cos(const N& u1, const N& a2) {
  using O = Num<N>;
  const N rest = N(1) - u1;
  return O::sqrt(O::max(N(0), rest / (rest + a2 * u1)));
}

// Beckman: tan²θm = −α_g² ln(1 − u1), cos θm = 1/√(1 + tan²θm).
template <class N>
N beckman_sample_cos(const N& u1, const N& a2) {
  using O = Num<N>;
  const N t2 = -(a2 * O::log_one_minus(u1));
  return N(1) / O::sqrt(N(1) + t2);
}

}  // namespace raylane::microfacet_steps
