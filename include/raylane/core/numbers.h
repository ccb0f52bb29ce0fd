// The number-type layer: the operations a step written once over its number type N calls, as
// Num<N>'s static functions, so that one text serves the double reference (N = double), its
// scalar float twin (N = float) and the float SIMD lanes (N = a batch of floats; the
// specialisation lives in simd/lane_numbers.h, for per-ISA translation units only). The shape
// is Mitsuba 3's: its Dr.Jit functions take scalars and arrays alike (Jakob et al., "Dr.Jit: A
// Just-In-Time Compiler for Differentiable Rendering", 2022). A class template rather than
// overloads: a specialisation declared after a step's template is still found where the step is
// instantiated, and this header needs no xsimd.
//
// Scalar versions call libm (the reference keeps its numbers); the lanes' versions carry the
// error bounds of simd/lane_math.h. Limits that depend on the type's range are members too.
//
// Integer steps (the Sobol sampler's hashes and scrambles, render/samplers/sobol_steps.h) are
// written over N = uint32_t or 32-bit unsigned lanes: +, ^, * and shifts are the operators of
// both, wrapping modulo 2^32, and Num<uint32_t> has the rest.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "raylane/core/float_util.h"

namespace raylane {

template <class N>
struct Num;

template <class T>
struct ScalarNum {
  using Mask = bool;
  static T select(bool c, T a, T b) { return c ? a : b; }
  static T max(T a, T b) { return std::max(a, b); }
  static T min(T a, T b) { return std::min(a, b); }
  static T sqrt(T x) { return std::sqrt(x); }
  static T abs(T x) { return std::abs(x); }
  static T round_even(T x) { return std::nearbyint(x); }  // to the nearest, ties to even
  static T negate(T x) { return -x; }                    // the sign bit flipped, zeros and NaNs too
  static bool sign_bit(T x) { return std::signbit(x); }  // −0 and −NaN too
  // e^-x for x ≥ 0.
  static T exp_neg(T x) { return std::exp(-x); }
  // ln(1 − u) for u in [0, 1]: −inf at 1.
  static T log_one_minus(T u) { return std::log1p(-std::min(u, T(1))); }
};

template <>
struct Num<double> : ScalarNum<double> {
  // x's neighbour on the side of `side`'s sign (next_double_up or next_double_down, core/
  // float_util.h: ±0 step to the least denormal, NaN and the infinity they move towards stay),
  // x itself where side is 0 or NaN.
  static double next_towards(double x, double side) {
    return side > 0 ? next_double_up(x) : side < 0 ? next_double_down(x) : x;
  }
  // Where e^-x is taken as 0: e^-700 ≈ 1e-304, below anything a cos⁻⁴ can lift into range.
  static constexpr double kExpNegCutoff = 700;
};

template <>
struct Num<float> : ScalarNum<float> {
  static float next_towards(float x, float side) {
    return side > 0 ? next_float_up(x) : side < 0 ? next_float_down(x) : x;
  }
  static constexpr float kExpNegCutoff = 80;  // e^-80 < 2e-35, near float's smallest normal
};

template <>
struct Num<uint32_t> {
  // x's 32 bits in reverse order: the bytes swapped, then the nibbles, bit pairs and bits of
  // each byte (Warren, "Hacker's Delight", 2nd ed., §7-1).
  static uint32_t reverse_bits(uint32_t x) {
    x = __builtin_bswap32(x);
    x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
    x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
    return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
  }
  // table[i], the scalar twin of a lane gather.
  static uint32_t gather(const uint32_t* table, uint32_t i) { return table[i]; }
  // No register permute: tables are read by gather (render/samplers/sobol_steps.h).
  static constexpr int kPermuteBits = 0;
  // x as float, for x below 2^31 (the lanes convert signed integers).
  using Float = float;
  static float to_float(uint32_t x) { return float(x); }
};

}  // namespace raylane
