// GGX and Beckman (render/materials/microfacet.h) in float lanes, for the lane BSDF
// (src/render/materials/shade_lanes_impl.h): the steps of render/materials/microfacet_steps.h, written once over the
// number type, instantiated at float lanes, with a mask `ggx` choosing GGX's lanes and Beckman's
// the others. Beckman's G1 needs nothing here: its a = 1/(α_g tan θv) = √(α/2 + 1)·cot θv under
// the course's conversion is the Phong lobe's a, so the kernel's g1() with its g1_scale column
// serves both. Lanes of Phong materials select the kernel's own values instead. Include only
// from src/render/materials/shade_lanes_impl.h.
#pragma once

#include "raylane/render/materials/microfacet_steps.h"
#include "raylane/simd/lane_numbers.h"

namespace raylane::detail::microfacet_lanes {

template <class A>
using F = simd::Floats<A>;
template <class A>
using M = simd::Mask<A>;

// D(m) and p(m) = D(m)·cos θm at c = cos θm (both 0 where c ≤ 0); ag2 = α_g².
template <class A>
void density(const M<A>& ggx, const F<A>& c, const F<A>& ag2, F<A>& d, F<A>& pm) {
  d = simd::select(ggx, microfacet_steps::ggx_density(c, ag2),
                   microfacet_steps::beckman_density(c, ag2));
  pm = d * xsimd::max(c, F<A>(0.0f));
}

template <class A>
F<A> ggx_g1(const F<A>& cos_v, const F<A>& cos_vm, const F<A>& ag2) {
  return microfacet_steps::ggx_g1(cos_v, cos_vm, ag2);
}

template <class A>
F<A> sample_cos(const M<A>& ggx, const F<A>& u1, const F<A>& ag2) {
  return simd::select(ggx, microfacet_steps::ggx_sample_cos(u1, ag2),
                      microfacet_steps::beckman_sample_cos(u1, ag2));
}

}  // namespace raylane::detail::microfacet_lanes
