// Float utilities for error bounds: neighbours, ulp distances, gamma(n) and the
// antisymmetric difference of products.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace raylane {

// Unit roundoff u = 2^-24 for float (pbrt-v4 `MachineEpsilon`, src/pbrt/util/float.h).
inline constexpr double kFloatUnitRoundoff = 0x1p-24;
inline constexpr double kDoubleUnitRoundoff = 0x1p-53;

// gamma(n) = n·u / (1 − n·u): the bound on the relative error of n chained float roundings
// (Higham, "Accuracy and Stability of Numerical Algorithms", §3.1; pbrt-v4 `gamma`).
constexpr double gamma_float(int n) {
  return n * kFloatUnitRoundoff / (1.0 - n * kFloatUnitRoundoff);
}

// The next float towards +inf. +inf and NaN are returned unchanged; −0 steps to the smallest
// positive denormal, like +0 (pbrt-v4 `NextFloatUp`). FLT_MAX steps to +inf, never to NaN
// (the madmann91/bvh #60 failure of an integer add on FLT_MAX's bits).
inline float next_float_up(float v) {
  if (std::isnan(v) || v == std::numeric_limits<float>::infinity()) return v;
  if (v == 0.0f) return std::numeric_limits<float>::denorm_min();
  uint32_t bits = std::bit_cast<uint32_t>(v);
  bits = v > 0.0f ? bits + 1 : bits - 1;
  return std::bit_cast<float>(bits);
}

inline float next_float_down(float v) {
  if (std::isnan(v) || v == -std::numeric_limits<float>::infinity()) return v;
  if (v == 0.0f) return -std::numeric_limits<float>::denorm_min();
  uint32_t bits = std::bit_cast<uint32_t>(v);
  bits = v > 0.0f ? bits - 1 : bits + 1;
  return std::bit_cast<float>(bits);
}

// The same for double: std::nextafter(v, ±inf) without the libm call (it was 1.7 % of a
// render, once per offset ray origin component).
inline double next_double_up(double v) {
  if (std::isnan(v) || v == std::numeric_limits<double>::infinity()) return v;
  if (v == 0.0) return std::numeric_limits<double>::denorm_min();
  uint64_t bits = std::bit_cast<uint64_t>(v);
  bits = v > 0.0 ? bits + 1 : bits - 1;
  return std::bit_cast<double>(bits);
}

inline double next_double_down(double v) {
  if (std::isnan(v) || v == -std::numeric_limits<double>::infinity()) return v;
  if (v == 0.0) return -std::numeric_limits<double>::denorm_min();
  uint64_t bits = std::bit_cast<uint64_t>(v);
  bits = v > 0.0 ? bits - 1 : bits + 1;
  return std::bit_cast<double>(bits);
}

// Maps a float onto a monotonic integer line (−0 and +0 both map to 0), so the distance in
// ulps between two floats is the difference of their keys.
inline int64_t float_ordered_key(float v) {
  int32_t bits = std::bit_cast<int32_t>(v);
  return bits >= 0 ? int64_t(bits) : -int64_t(bits & 0x7fffffff);
}

// Number of representable floats between a and b; NaN in either gives the maximum.
inline uint64_t ulp_distance(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<uint64_t>::max();
  int64_t d = float_ordered_key(a) - float_ordered_key(b);
  return uint64_t(d < 0 ? -d : d);
}

// a·b − c·d within 1.5 ulp (Kahan's algorithm; Jeannerod, Louvet and Muller 2013, "Further
// analysis of Kahan's algorithm for the accurate computation of 2×2 determinants"), so its
// sign is always the exact sign: sign(dop(a,b,c,d)) == −sign(dop(c,d,a,b)). A contracted
// fma(a, b, −c·d) lacks that antisymmetry, which is what opens cracks between triangles that
// share an edge (docs/hard-cases.md T2). pbrt-v4 uses the same `DifferenceOfProducts`.
template <class T>
inline T difference_of_products(T a, T b, T c, T d) {
  T cd = c * d;
  T err = std::fma(-c, d, cd);
  T dop = std::fma(a, b, -cd);
  return dop + err;
}

}  // namespace raylane
