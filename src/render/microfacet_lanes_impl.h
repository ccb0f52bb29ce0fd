// GGX and Beckman (render/microfacet.h) in float lanes, for the lane BSDF
// (src/render/shade_lanes_impl.h): D and the density of m, GGX's Smith G1, and the warp of
// cos θm. Beckman's G1 needs nothing here: its a = 1/(α_g tan θv) = √(α/2 + 1)·cot θv under the
// course's conversion is the Phong lobe's a, so the kernel's g1() with its g1_scale column
// serves both. Every function takes a mask `ggx` (GGX in those lanes, Beckman in the others)
// and α_g²; lanes of Phong materials select the kernel's own values instead. Include only from
// src/render/shade_lanes_impl.h.
#pragma once

#include "raylane/simd/lane_math.h"

namespace raylane::detail::microfacet_lanes {

template <class A>
using F = simd::Floats<A>;
template <class A>
using M = simd::Mask<A>;

// D(m) and p(m) = D(m)·cos θm at c = cos θm (both 0 where c ≤ 0). GGX as
// α_g²/(π (α_g² cos²θm + sin²θm)²), finite at the horizon; Beckman
// exp(−tan²θm/α_g²)/(π α_g² cos⁴θm), taken as 0 where the exponent passes 80 (e^-80 < 2e-35,
// and cos θm is then > 1/9 for α_g ≤ 1, so nothing divides by a vanishing cos⁴).
template <class A>
void density(const M<A>& ggx, const F<A>& c, const F<A>& ag2, F<A>& d, F<A>& pm) {
  const F<A> zero(0.0f), one(1.0f), inv_pi(0.318309886183790671538f);
  F<A> cp = xsimd::max(c, zero);
  F<A> c2 = xsimd::min(one, cp * cp), s2 = one - c2;
  F<A> den = ag2 * c2 + s2;
  F<A> d_ggx = ag2 * inv_pi / (den * den);
  F<A> e = s2 / (c2 * ag2);
  M<A> kept = e < F<A>(80.0f);
  F<A> ex = simd::exp2<A>(xsimd::max(e, zero) * F<A>(-1.44269504088896340736f));  // e^-e
  F<A> d_beckman = ex * inv_pi / (ag2 * c2 * c2);
  d = simd::select(c > zero, simd::select(ggx, d_ggx, simd::select(kept, d_beckman, zero)), zero);
  pm = d * cp;
}

// GGX's Smith G1 = 2/(1 + √(1 + α_g² tan²θv)), 0 for a back-facing microfacet
// ((v·m)(v·n) ≤ 0); at cos θv = 0, tan²θv = inf gives 0.
template <class A>
F<A> ggx_g1(const F<A>& cos_v, const F<A>& cos_vm, const F<A>& ag2) {
  const F<A> zero(0.0f), one(1.0f);
  F<A> c2 = cos_v * cos_v;
  F<A> t2 = xsimd::max(zero, one - c2) / c2;
  F<A> r = F<A>(2.0f) / (one + xsimd::sqrt(one + ag2 * t2));
  return simd::select(cos_vm * cos_v > zero, r, zero);
}

// cos θm drawn with density D(m)·cos θm from u1 in [0, 1): GGX's tan²θm = α_g²u1/(1 − u1) as
// cos²θm = (1 − u1)/(1 − u1 + α_g²u1); Beckman's tan²θm = −α_g² ln(1 − u1).
template <class A>
F<A> sample_cos(const M<A>& ggx, const F<A>& u1, const F<A>& ag2) {
  const F<A> one(1.0f);
  F<A> rest = one - u1;
  F<A> c2_ggx = rest / (rest + ag2 * u1);
  F<A> ln_rest = simd::log2<A>(xsimd::max(rest, F<A>(0x1p-126f))) * F<A>(0.69314718055994530942f);
  F<A> c2_beckman = one / (one - ag2 * ln_rest);
  return xsimd::sqrt(simd::select(ggx, c2_ggx, c2_beckman));
}

}  // namespace raylane::detail::microfacet_lanes
