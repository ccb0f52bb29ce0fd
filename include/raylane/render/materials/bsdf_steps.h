// Steps of the course's BSDF (render/materials/bsdf.h) written once over the number type N
// (core/numbers.h): the double Bsdf (src/render/materials/bsdf.cpp) instantiates them at double, the lane
// BSDF (src/render/materials/shade_lanes_impl.h) at float lanes. Branches are selects.
#pragma once

#include "raylane/core/numbers.h"

namespace raylane::bsdf_steps {

// Walter et al. 2007, eq. 27: the rational approximation of the Smith G1 of the Beckmann lobe,
// for the Phong lobe through a = √(α/2 + 1)·cot θv (scale = √(α/2 + 1)). 0 for a microfacet
// back-facing from v ((v·m)(v·n) ≤ 0); 1 where a > 1.6, and where sin θv = 0 (a = inf).
template <class N>
N rational_smith_g1(const N& cos_v, const N& cos_vm, const N& scale) {
  using O = Num<N>;
  const N sin_v = O::sqrt(O::max(N(0), N(1) - cos_v * cos_v));
  const N a = scale * O::abs(cos_v) / sin_v;
  const N r = (N(3.535) * a + N(2.181) * a * a) / (N(1) + N(2.276) * a + N(2.577) * a * a);
  return O::select(cos_vm * cos_v > N(0), O::select(a > N(1.6), N(1), r), N(0));
}

// Schlick's (1 − |cos θ|)^5 (F = Ks + (1 − Ks)·this), by multiplication: pow does not inline.
template <class N>
N schlick_weight(const N& cos_om) {
  using O = Num<N>;
  const N x = N(1) - O::min(N(1), O::abs(cos_om)), x2 = x * x;
  return x2 * x2 * x;
}

}  // namespace raylane::bsdf_steps
