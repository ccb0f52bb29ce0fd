// The number-type layer (core/numbers.h) for lanes: Num<simd::Floats<A>>, Num<simd::Doubles<A>>
// and Num<simd::UInts<A>>, so that a step written once over its number type runs in lanes.
// Include only from per-ISA translation units (simd/lanes.h). The float lanes' exp_neg and
// log_one_minus carry the bounds of simd/lane_math.h's exp2 and log2.
#pragma once

#include "raylane/core/numbers.h"
#include "raylane/simd/lane_math.h"

namespace raylane {

template <class A>
struct Num<xsimd::batch<float, A>> {
  using F = simd::Floats<A>;
  using Mask = simd::Mask<A>;
  static F select(const Mask& c, const F& a, const F& b) { return simd::select(c, a, b); }
  static F max(const F& a, const F& b) { return xsimd::max(a, b); }
  static F min(const F& a, const F& b) { return xsimd::min(a, b); }
  static F sqrt(const F& x) { return xsimd::sqrt(x); }
  static F abs(const F& x) { return xsimd::abs(x); }
  // e^-x = 2^(−x·log2 e), x ≥ 0 (a negative x is taken as 0).
  static F exp_neg(const F& x) {
    return simd::exp2<A>(xsimd::max(x, F(0.0f)) * F(-1.44269504088896340736f));
  }
  // ln(1 − u) = log2(1 − u)·ln 2, 1 − u held at 2^-126 (log2 takes normal numbers): at u = 1
  // it is −87.3 rather than −inf.
  static F log_one_minus(const F& u) {
    return simd::log2<A>(xsimd::max(F(1.0f) - u, F(0x1p-126f))) * F(0.69314718055994530942f);
  }
  static constexpr float kExpNegCutoff = 80;
};

// Double lanes: the operations the double steps in lanes call so far (the pinhole camera's
// direction, render/camera/camera.h). sqrt is correctly rounded, as std::sqrt.
template <class A>
struct Num<xsimd::batch<double, A>> {
  using D = simd::Doubles<A>;
  static D sqrt(const D& x) { return simd::sqrt<A>(x); }
};

// 32-bit unsigned lanes, for the integer steps (Num<uint32_t>'s twins).
template <class A>
struct Num<xsimd::batch<uint32_t, A>> {
  using U = simd::UInts<A>;
  static U reverse_bits(const U& x) { return simd::reverse_bits<A>(x); }
  static U gather(const uint32_t* table, const U& i) { return simd::gather<A>(table, i); }
};

}  // namespace raylane
