// The arithmetic after a vertex's BSDF, written once over the number type: N = double for the
// double shading (render/vertex_lanes.h's shadow_contribution and next_throughput), N = float for
// the lanes' scalar reference, N = a batch of float lanes for the scatter kernel
// (src/render/vertex_lanes_impl.h); V3 is its 3-vector (glm::dvec3, glm::vec3, simd::FloatVec3).
// One text for all, so they agree bit for bit by construction (the build has
// -ffp-contract=off). What to keep stays with each caller: the scalar steps return early, the
// lanes carry a mask. This header has no xsimd: Num<N> (core/numbers.h) names the operations.
#pragma once

#include "raylane/core/numbers.h"

namespace raylane {

// Veach's power heuristic with β = 2 (Veach 1997, thesis §9.2.4) for one sample of each,
// p²/(p² + q²) taken as 1/(1 + (q/p)²) so that no square overflows or underflows in float
// (densities of 1e20 are a small light far off): 0 where pdf_this is not positive (or NaN).
template <class N>
N power_heuristic(const N& pdf_this, const N& pdf_other) {
  const N r = pdf_other / pdf_this;
  return Num<N>::select(pdf_this > N(0.0), N(1.0) / (N(1.0) + r * r), N(0.0));
}

// A shadow ray's contribution if it sees the light: beta·f·Le·(w / light_pdf), w the power
// heuristic under MIS, else 1.
template <class N, class V3>
V3 shadow_ray_contribution(bool mis, const V3& beta, const V3& f, const V3& le, const N& light_pdf,
                           const N& bsdf_pdf) {
  const N w = mis ? power_heuristic(light_pdf, bsdf_pdf) : N(1.0);
  const N scale = w / light_pdf;
  return V3{beta.x * f.x * le.x * scale, beta.y * f.y * le.y * scale, beta.z * f.z * le.z * scale};
}

// The throughput after the BSDF's sample: beta·value / pdf.
template <class N, class V3>
V3 sampled_throughput(const V3& beta, const V3& value, const N& pdf) {
  return V3{beta.x * value.x / pdf, beta.y * value.y / pdf, beta.z * value.z / pdf};
}

// The throughput of a path that survived Russian roulette with probability `survival`.
template <class N, class V3>
V3 survivor_throughput(const V3& beta, const N& survival) {
  return V3{beta.x / survival, beta.y / survival, beta.z / survival};
}

}  // namespace raylane
