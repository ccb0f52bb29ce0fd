// The light sample that a point drawn by area on an emitter makes from a shading point, written
// once over the number type (core/numbers.h): N = double for the double shading (LightSampler's
// conversion by area, every kind sampled by area), N = float lanes for a box light's points
// (src/render/lights/light_lanes_impl.h), and N = float as the lanes' bit-for-bit reference. No
// step fuses a multiply-add and the build has -ffp-contract=off, so the float lanes and the
// scalar float text agree on every instruction set.
//
// The density by area, converted to solid angle (Veach 1997, §5.4; pbrt-v4 §4.2.3): choice ·
// d² / (cos θ_light · area), θ_light the angle at the light between its normal and the
// direction back to the shading point.
#pragma once

#include <cmath>

#include "raylane/core/numbers.h"

namespace raylane {

// The unit direction, the distance, and the density in solid angle; pdf 0 where the point is
// no sample: an area of 0, the point at ref, the point seen edge-on or from behind (one-sided
// kinds; kTwoSided takes |cos θ_light|), or a density beyond the type's range.
template <class N, class V3>
struct AreaLightSample {
  V3 wi;
  N dist, pdf;
};

template <bool kTwoSided, class N, class V3>
AreaLightSample<N, V3> area_light_sample(const V3& ref, const V3& p, const V3& n, const N& area,
                                         const N& choice) {
  using K = Num<N>;
  using M = typename K::Mask;
  const N zero(0.0);
  const V3 to{p.x - ref.x, p.y - ref.y, p.z - ref.z};
  const N d2 = to.x * to.x + to.y * to.y + to.z * to.z;
  const N dist = K::sqrt(d2);
  AreaLightSample<N, V3> out;
  out.wi = V3{to.x / dist, to.y / dist, to.z / dist};
  out.dist = dist;
  N cos_l = K::negate(out.wi.x * n.x + out.wi.y * n.y + out.wi.z * n.z);
  if constexpr (kTwoSided) cos_l = K::abs(cos_l);
  const N pdf = choice * d2 / (cos_l * area);
  // The comparison with infinity is false for NaN too.
  const M ok = M(M(M((area > zero) & (d2 > zero)) & (cos_l > zero)) & (pdf < N(HUGE_VAL)));
  out.pdf = K::select(ok, pdf, zero);
  return out;
}

}  // namespace raylane
