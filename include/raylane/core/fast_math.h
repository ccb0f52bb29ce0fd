// sin and cos of the azimuth every warp draws, without libm's general path (reduction of huge
// arguments): libm's sincos weighed on a render's profile, and this costs half as much
// (docs/design.md, "The course's rendering model"). Double precision with a stated error bound,
// checked against long double in fast_math_test.cpp. (libm's pow stays: per call it is faster than
// a polynomial exp2/log2 in double in scalar code; the lobes call it less often instead, see
// Bsdf::evaluate.)
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

namespace raylane {

struct SinCos {
  double sin, cos;
};

namespace fast_math_detail {

// Taylor polynomials of sin and cos about 0 (Horner form), for |a| ≤ π/4: the first omitted
// terms are below a^17/17! ≤ 4.6e-17 and a^18/18! ≤ 2e-18, under half an ulp of the results.
// Templates so that double SIMD lanes (render/lights/light_lanes.h) evaluate the same polynomials.
template <class T>
T sin_poly(T a) {
  T a2 = a * a;
  T p = T(-1.0 / 1307674368000);  // −1/15!
  p = p * a2 + 1.0 / 6227020800;  // 1/13!
  p = p * a2 - 1.0 / 39916800;    // −1/11!
  p = p * a2 + 1.0 / 362880;      // 1/9!
  p = p * a2 - 1.0 / 5040;        // −1/7!
  p = p * a2 + 1.0 / 120;
  p = p * a2 - 1.0 / 6;
  return a + a * a2 * p;
}

template <class T>
T cos_poly(T a) {
  T a2 = a * a;
  T p = T(1.0 / 20922789888000);   // 1/16!
  p = p * a2 - 1.0 / 87178291200;  // −1/14!
  p = p * a2 + 1.0 / 479001600;    // 1/12!
  p = p * a2 - 1.0 / 3628800;      // −1/10!
  p = p * a2 + 1.0 / 40320;        // 1/8!
  p = p * a2 - 1.0 / 720;
  p = p * a2 + 1.0 / 24;
  return T(1.0) - T(0.5) * a2 + a2 * a2 * p;
}

}  // namespace fast_math_detail

// sin and cos of 2π·u for u in [0, 1] (the azimuth of every warp). The turn is reduced
// exactly to a quarter q and a remainder r = u − q/4 with |r| ≤ 1/8 (both exact in double),
// so only 2π·r rounds: the absolute error is below 3e-16 for every u (the test's bound),
// less than std::sin(2π·u), whose argument 2π·u alone rounds by up to 4.4e-16.
inline SinCos sincos_2pi(double u) {
  constexpr double kTwoPi = 6.283185307179586476925;
  double q = std::nearbyint(4 * u);
  double a = kTwoPi * (u - 0.25 * q);
  double s = fast_math_detail::sin_poly(a), c = fast_math_detail::cos_poly(a);
  // The quarter turns, (s, c) → (c, −s) → (−s, −c) → (−c, s), by selects and sign flips rather
  // than a switch: the quarter of a sampled azimuth is random, and the switch's mispredictions
  // were a tenth of the sky scene's (callgrind, branch simulation).
  // Exact: the selects take one value's bits or the other's by a mask, and the signs multiply
  // by ±1 (GCC made branches of conditional selects and negations; a pair in memory indexed by
  // the quarter stalled on the store's forwarding).
  const int64_t quarter = int64_t(q);
  const uint64_t odd = uint64_t(0) - uint64_t(quarter & 1);  // all ones for an odd quarter
  const uint64_t sb = std::bit_cast<uint64_t>(s), cb = std::bit_cast<uint64_t>(c);
  const double sin = std::bit_cast<double>((sb & ~odd) | (cb & odd));
  const double cos = std::bit_cast<double>((cb & ~odd) | (sb & odd));
  return {sin * double(1 - (quarter & 2)), cos * double(1 - ((quarter + 1) & 2))};
}

}  // namespace raylane
