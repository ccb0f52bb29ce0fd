// Two steps of the warps written once over the number type (core/numbers.h), for steps that
// are themselves written once (prims/sphere_cone.h): the sine and cosine of a turn and the
// orthonormal frame about a unit normal. At double they give core/fast_math.h's sincos_2pi and
// core/warps.h's Frame bit for bit; the float lanes' BSDF still has its own (simd/lane_math.h's
// sincos_2pi, with fused multiply-adds, and simd::to_world), the same formulas.
#pragma once

#include <type_traits>

#include "raylane/core/fast_math.h"
#include "raylane/core/numbers.h"

namespace raylane {

// Whether N is double or double lanes (else float or float lanes).
template <class N>
constexpr bool is_double_number() {
  if constexpr (std::is_arithmetic_v<N>)
    return std::is_same_v<N, double>;
  else
    return std::is_same_v<typename N::value_type, double>;
}

template <class N>
struct TurnSinCos {
  N sin, cos;
};

// sin and cos of 2π·u for u in [0, 1], as core/fast_math.h's sincos_2pi: the turn reduced
// exactly to a quarter q = round(4u) and |u − q/4| ≤ 1/8 (Sterbenz), Taylor polynomials on
// |a| ≤ π/4, then the quarter's symmetry. In double fast_math's polynomials (the same answers,
// bit for bit); in float the same series to degree 9 and 10 (the omitted terms are below 2e-9),
// in plain products and sums: absolute error ≤ 3·2^-24, as simd/lane_math.h's.
template <class N>
TurnSinCos<N> sincos_turn(const N& u) {
  using K = Num<N>;
  constexpr double kTwoPi = 6.283185307179586476925;
  const N q = K::round_even(N(4.0) * u);
  const N a = N(kTwoPi) * (u - N(0.25) * q);
  N s, c;
  if constexpr (is_double_number<N>()) {
    s = fast_math_detail::sin_poly(a), c = fast_math_detail::cos_poly(a);
  } else {
    const N a2 = a * a;
    N ps = N(1.0f / 362880) * a2 - N(1.0f / 5040);
    ps = ps * a2 + N(1.0f / 120);
    ps = ps * a2 - N(1.0f / 6);
    s = a + a * a2 * ps;
    N pc = N(-1.0f / 3628800) * a2 + N(1.0f / 40320);
    pc = pc * a2 - N(1.0f / 720);
    pc = pc * a2 + N(1.0f / 24);
    c = N(1.0f) - N(0.5f) * a2 + a2 * a2 * pc;
  }
  // Quarter k = q mod 4 (q is 0 to 4): (sin, cos) = (s, c), (c, −s), (−s, −c), (−c, s).
  const N k = K::select(q == N(4.0), N(0.0), q);
  using Mask = typename K::Mask;
  const Mask swap = (k == N(1.0)) | (k == N(3.0));
  const Mask neg_sin = k >= N(2.0), neg_cos = (k == N(1.0)) | (k == N(2.0));
  const N sin = K::select(swap, c, s), cos = K::select(swap, s, c);
  return {K::select(neg_sin, K::negate(sin), sin), K::select(neg_cos, K::negate(cos), cos)};
}

// The local direction v = (x, y, z) about the unit normal n, to world: Duff et al. 2017,
// "Building an Orthonormal Basis, Revisited", in core/warps.h's Frame's order. Inlined always:
// GCC called it from the cone kernel, its vectors passed and returned through memory
// (bench/README.md, "The surfaces' rows read in place, ...").
template <class N, class V3>
[[gnu::always_inline]] inline V3 frame_to_world(const V3& n, const V3& v) {
  using K = Num<N>;
  const N sign = K::select(K::sign_bit(n.z), N(-1.0), N(1.0));
  const N a = N(-1.0) / (sign + n.z);
  const N b = n.x * n.y * a;
  const N minus_sign = K::negate(sign);
  const V3 s{N(1.0) + sign * n.x * n.x * a, sign * b, minus_sign * n.x};
  const V3 t{b, sign + n.y * n.y * a, K::negate(n.y)};
  return V3{s.x * v.x + t.x * v.y + n.x * v.z, s.y * v.x + t.y * v.y + n.y * v.z,
            s.z * v.x + t.z * v.y + n.z * v.z};
}

}  // namespace raylane
