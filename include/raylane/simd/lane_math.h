// The render loop's transcendentals in float lanes (docs/design.md, "Shading in lanes"): sin and
// cos of a turn, log2, exp2 and pow for the Phong lobe, each with a stated error bound that
// tests/simd/lane_math_test.cpp checks against double. Written for any lane width, like the
// kernels; include only from per-ISA translation units (simd/lanes.h).
//
// Bounds, for results of normal size (below 2^-126 results flush to 0):
//   sincos_2pi: absolute error ≤ 3·2^-24 (the reduction is exact; the polynomials' truncation
//               is below 2^-31, the rest is float rounding in Horner's scheme).
//   log2:       relative error ≤ 4.5·2^-24 (the exponent is exact; the mantissa's logarithm,
//               a series in s = (m−1)/(m+1), is within 4·2^-24 relative: m + 1, the division,
//               the constant 2/ln 2, its product and the last fma each round once; where the
//               exponent is not 0 that fma adds the two, and |log2 x| ≥ ½ there).
//   exp2:       relative error ≤ 2·2^-24 on [−126, 127].
//   pow(x, y) = exp2(y·log2 x) for x in [0, 1], y ≥ 0: relative error ≤ (3 + 3.5·|y·log2 x|)·2^-24.
//               The exponent t = y·log2 x carries log2's 4.5·2^-24 and the product's half ulp,
//               and exp2 turns an absolute error δ of t into a relative ln 2·δ of the result
//               (ln 2 · 5 < 3.5). For the Phong lobe's cos^α θm this is largest where the lobe has
//               already fallen to 2^-|t| of its peak.
#pragma once

#include "raylane/simd/lanes.h"

namespace raylane::simd {

template <class A>
struct LaneSinCos {
  Floats<A> sin, cos;
};

// sin and cos of 2π·u for u in [0, 1]. As core/fast_math.h's double version: the turn is
// reduced exactly to a quarter q = round(4u) and r = u − q/4, |r| ≤ 1/8 (exact by Sterbenz's
// lemma), then Taylor polynomials on |2πr| ≤ π/4 to degree 9 and 10 (omitted terms below
// 1.6e-10 and 1.2e-10), and the quadrant's symmetry.
template <class A>
inline LaneSinCos<A> sincos_2pi(const Floats<A>& u) {
  using F = Floats<A>;
  F q = xsimd::nearbyint(u * F(4.0f));
  F a = (u - q * F(0.25f)) * F(6.28318530717958647692f);
  F a2 = a * a;
  F ps = fma(F(1.0f / 362880), a2, F(-1.0f / 5040));
  ps = fma(ps, a2, F(1.0f / 120));
  ps = fma(ps, a2, F(-1.0f / 6));
  F s = fma(a * a2, ps, a);
  F pc = fma(F(-1.0f / 3628800), a2, F(1.0f / 40320));
  pc = fma(pc, a2, F(-1.0f / 720));
  pc = fma(pc, a2, F(1.0f / 24));
  F c = fma(a2 * a2, pc, fma(a2, F(-0.5f), F(1.0f)));
  // Quadrant k = q mod 4: (sin, cos) = (s, c), (c, −s), (−s, −c), (−c, s).
  F k = select(q == F(4.0f), F(0.0f), q);
  Mask<A> swap = (k == F(1.0f)) | (k == F(3.0f));
  Mask<A> neg_sin = k >= F(2.0f), neg_cos = (k == F(1.0f)) | (k == F(2.0f));
  F sin = select(swap, c, s), cos = select(swap, s, c);
  return {select(neg_sin, -sin, sin), select(neg_cos, -cos, cos)};
}

// log2 x for normal x > 0: x = 2^e·m with m in [√½, √2), log2 m = (2/ln 2)·atanh s with
// s = (m − 1)/(m + 1), |s| ≤ 0.172, by its series to s^9 (the next term is below 2^-30
// relative to s). m − 1 is exact (Sterbenz).
template <class A>
inline Floats<A> log2(const Floats<A>& x) {
  using F = Floats<A>;
  using I = Ints<A>;
  I bits = xsimd::bitwise_cast<I>(x);
  I e = (bits >> 23) - I(127);
  F m = xsimd::bitwise_cast<F>((bits & I(0x7fffff)) | I(0x3f800000));
  Mask<A> big = m > F(1.41421356237309504880f);
  m = select(big, m * F(0.5f), m);
  F ef = xsimd::batch_cast<float>(e) + select(big, F(1.0f), F(0.0f));
  F s = (m - F(1.0f)) / (m + F(1.0f));
  F s2 = s * s;
  F p = fma(F(1.0f / 9), s2, F(1.0f / 7));
  p = fma(p, s2, F(1.0f / 5));
  p = fma(p, s2, F(1.0f / 3));
  p = fma(p, s2, F(1.0f));
  return fma(s * F(2.88539008177792681472f), p, ef);  // 2/ln 2
}

// 2^t for t in [−126, 127] (0 below −126): t = n + f with n = round(t), |f| ≤ ½, and 2^f by
// the Taylor series of e^(f·ln 2) to degree 7 (the next term is below 2^-27), scaled by 2^n
// through the exponent bits.
template <class A>
inline Floats<A> exp2(const Floats<A>& t) {
  using F = Floats<A>;
  using I = Ints<A>;
  F tc = xsimd::min(xsimd::max(t, F(-127.0f)), F(127.0f));
  F n = xsimd::nearbyint(tc);
  F f = (tc - n) * F(0.69314718055994530942f);
  F p = fma(F(1.0f / 5040), f, F(1.0f / 720));
  p = fma(p, f, F(1.0f / 120));
  p = fma(p, f, F(1.0f / 24));
  p = fma(p, f, F(1.0f / 6));
  p = fma(p, f, F(0.5f));
  p = fma(p, f, F(1.0f));
  p = fma(p, f, F(1.0f));
  I scale_bits = (xsimd::batch_cast<int32_t>(n) + I(127)) << 23;
  F r = p * xsimd::bitwise_cast<F>(scale_bits);
  return select(tc < F(-126.0f), F(0.0f), r);
}

// x^y for x in [0, 1], y ≥ 0 (0^0 = 1, as std::pow): exp2(y·log2 x).
template <class A>
inline Floats<A> pow_unit(const Floats<A>& x, const Floats<A>& y) {
  using F = Floats<A>;
  F r = exp2(y * log2(x));
  r = select(x > F(0.0f), r, F(0.0f));
  return select(y == F(0.0f), F(1.0f), r);
}

}  // namespace raylane::simd
