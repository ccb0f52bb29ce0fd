// The number-type layer (core/numbers.h) for lanes: Num<simd::Floats<A>>, Num<simd::Doubles<A>>
// and Num<simd::UInts<A>>, so that a step written once over its number type runs in lanes.
// Include only from per-ISA translation units (simd/lanes.h). The float lanes' exp_neg and
// log_one_minus carry the bounds of simd/lane_math.h's exp2 and log2.
#pragma once

#include "raylane/core/numbers.h"
#include "raylane/simd/lane_lookup.h"
#include "raylane/simd/lane_math.h"

namespace raylane {

template <class A>
struct Num<xsimd::batch<float, A>> {
  using F = simd::Floats<A>;
  using Mask = simd::Mask<A>;
  static F select(const Mask& c, const F& a, const F& b) { return simd::select(c, a, b); }
  // std::max(a, b) and std::min(a, b) exactly, NaNs and zeros' signs included: MAXPS(x, y) and
  // MINPS(x, y) return y where either is NaN or both are zero, so the operands go in swapped
  // ((b > a) ? b : a is std::max's (a < b) ? b : a).
  static F max(const F& a, const F& b) { return simd::max_keep<A>(b, a); }
  static F min(const F& a, const F& b) { return simd::min_keep<A>(b, a); }
  static F sqrt(const F& x) { return simd::sqrt<A>(x); }  // simd/lanes.h: no -Wuninitialized
  static F abs(const F& x) { return xsimd::abs(x); }
  static F round_even(const F& x) { return xsimd::nearbyint(x); }
  // Not unary minus, which xsimd 8.1 makes 0 − x on AVX-512 (+0 stays +0; simd/lanes.h).
  static F negate(const F& x) { return simd::negate(x); }
  static Mask sign_bit(const F& x) { return xsimd::copysign(F(1.0f), x) < F(0.0f); }
  // e^-x = 2^(−x·log2 e), x ≥ 0 (a negative x is taken as 0).
  static F exp_neg(const F& x) {
    return simd::exp2<A>(xsimd::max(x, F(0.0f)) * F(-1.44269504088896340736f));
  }
  // ln(1 − u) = log2(1 − u)·ln 2, 1 − u held at 2^-126 (log2 takes normal numbers): at u = 1
  // it is −87.3 rather than −inf.
  static F log_one_minus(const F& u) {
    return simd::log2<A>(xsimd::max(F(1.0f) - u, F(0x1p-126f))) * F(0.69314718055994530942f);
  }
  // next_towards (core/numbers.h) per lane, one step instead of two: up the magnitude where x
  // lies on side's side, down it where not (both nonzero); ±0 to the least denormal of side's
  // sign; NaN, and an infinity growing, unchanged; x where side is 0 or NaN.
  static F next_towards(const F& x, const F& side) {
    using I = xsimd::batch<int32_t, A>;
    const F zero(0.0f);
    const auto up = side > zero, down = side < zero;
    const auto grows = ((x > zero) & up) | ((x < zero) & down);
    const I bits = xsimd::bitwise_cast<I>(x);
    const F stepped = xsimd::select(grows, xsimd::bitwise_cast<F>(bits + I(1)),
                                    xsimd::bitwise_cast<F>(bits - I(1)));
    const F from_zero = xsimd::select(up, F(0x1p-149f), F(-0x1p-149f));
    const auto stays = xsimd::isnan(x) | (grows & (xsimd::abs(x) == F(HUGE_VALF)));
    const F moved = xsimd::select(x == zero, from_zero, xsimd::select(stays, x, stepped));
    return xsimd::select(up | down, moved, x);
  }
  static constexpr float kExpNegCutoff = 80;
};

// Double lanes: what the double steps in lanes call (the kinds' surfaces, prims/<kind>.h; the
// float bound of a double point, core/ray_offset.h; the pinhole camera's direction,
// render/camera/camera.h). sqrt is correctly rounded, as std::sqrt.
template <class A>
struct Num<xsimd::batch<double, A>> {
  using D = simd::Doubles<A>;
  using Mask = xsimd::batch_bool<double, A>;
  static D select(const Mask& c, const D& a, const D& b) { return xsimd::select(c, a, b); }
  static D sqrt(const D& x) { return simd::sqrt<A>(x); }
  // std::max's and std::min's choices, NaNs included: (a < b ? b : a) and (b < a ? b : a).
  static D max(const D& a, const D& b) { return xsimd::select(a < b, b, a); }
  static D min(const D& a, const D& b) { return xsimd::select(b < a, b, a); }
  static D abs(const D& x) { return xsimd::abs(x); }
  static D negate(const D& x) { return simd::negate(x); }
  static Mask sign_bit(const D& x) { return simd::sign_bit<A>(x); }
};

// 32-bit unsigned lanes, for the integer steps (Num<uint32_t>'s twins).
template <class A>
struct Num<xsimd::batch<uint32_t, A>> {
  using U = simd::UInts<A>;
  static U reverse_bits(const U& x) { return simd::reverse_bits<A>(x); }
  static U gather(const uint32_t* table, const U& i) { return simd::gather<A>(table, i); }
  // table[i mod 2^kPermuteBits] by one register permute (simd/lane_lookup.h); 0 bits: none.
  static constexpr int kPermuteBits = simd::kPermuteIndexBits<A>;
  static U permute(const uint32_t* table, const U& i) { return simd::permute_words<A>(table, i); }
  using Float = simd::Floats<A>;
  static Float to_float(const U& x) {
    return xsimd::to_float(xsimd::bitwise_cast<simd::Ints<A>>(x));
  }
};

}  // namespace raylane
