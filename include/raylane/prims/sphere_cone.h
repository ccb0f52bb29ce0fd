// A point on a sphere light by the cone the sphere subtends, written once over the number type
// (core/numbers.h): N = double for the double shading (sample_sphere_cone, prims/sphere.h), N =
// float lanes for the render's light points (src/render/lights/light_lanes_impl.h), and N =
// float as the lanes' bit-for-bit reference. No step fuses a multiply-add and the build has
// -ffp-contract=off, so the float lanes and the scalar float text agree on every instruction
// set.
//
// Float's error, for a sphere of radius r seen from distance d > r (each step rounds once, to
// 2^-24 relative; tests/render/light_lanes_test.cpp holds the float answers to these against
// the double ones at the same inputs):
//   - the direction: a few float roundoffs (the cone's frame and sin/cos of the turn);
//   - the distance d·cos θ − √(r² − d²sin²θ): the difference of two terms of size d, so a few
//     roundoffs of d, not of the distance;
//   - the solid angle 2π·sin²θmax / (1 + cos θmax) (no cancellation for a narrow cone: pbrt-v4,
//     Pharr, Jakob and Humphreys, 4th ed., §6.2.4): a few roundoffs relative.
#pragma once

#include "raylane/core/frame_steps.h"
#include "raylane/core/numbers.h"

namespace raylane {

// 1 − cos θmax of the cone a sphere of radius² r2 subtends from distance² d2 > r2, as
// sin²θmax / (1 + cos θmax): no cancellation for a narrow cone.
template <class N>
N cone_one_minus_cos(const N& r2, const N& d2) {
  using K = Num<N>;
  const N sin2_max = r2 / d2;
  return sin2_max / (N(1.0) + K::sqrt(K::max(N(0.0), N(1.0) - sin2_max)));
}

// A direction toward a sphere, uniform in the cone it subtends, and how far along it the sphere
// lies; solid_angle 0 where the reference point is not outside the sphere (the caller samples
// by area there, and wi and dist are then meaningless).
template <class N, class V3>
struct SphereCone {
  V3 wi;
  N dist, solid_angle;
};

// The sphere about `center` of radius r, seen from ref, with the cone's numbers u1 (1 − cos θ
// over its range) and u2 (the turn about the axis). Inlined always, as frame_to_world: with
// that one inlined alone, GCC called this and sincos_turn out of line from the cone kernel.
template <class N, class V3>
[[gnu::always_inline]] inline SphereCone<N, V3> sphere_cone(const V3& center, const N& r,
                                                            const V3& ref, const N& u1,
                                                            const N& u2) {
  using K = Num<N>;
  const N zero(0.0), one(1.0);
  const V3 w{center.x - ref.x, center.y - ref.y, center.z - ref.z};
  const N r2 = r * r, d2 = w.x * w.x + w.y * w.y + w.z * w.z;
  const auto outside = d2 > r2;
  const N d = K::sqrt(d2);
  const N omc_max = cone_one_minus_cos(r2, d2);
  // Uniform in the cone: 1 − cos θ = u1·(1 − cos θmax), sin²θ = (1 − cos θ)(1 + cos θ).
  const N omc = u1 * omc_max;
  const N cos_t = one - omc;
  const N sin_t = K::sqrt(K::max(zero, omc * (N(2.0) - omc)));
  const TurnSinCos<N> phi = sincos_turn(u2);
  const V3 local{sin_t * phi.cos, sin_t * phi.sin, cos_t};
  // The nearer root of the ray from ref along the sampled direction.
  const N sin2 = local.x * local.x + local.y * local.y;
  const N t_hit = d * local.z - K::sqrt(K::max(zero, r2 - d2 * sin2));
  const V3 axis{w.x / d, w.y / d, w.z / d};
  constexpr double kTwoPi = 6.283185307179586476925;
  return {frame_to_world<N>(axis, local), t_hit, K::select(outside, N(kTwoPi) * omc_max, zero)};
}

}  // namespace raylane
