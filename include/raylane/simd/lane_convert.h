// Float lanes to double lanes and back, through memory: a kernel that computes in one precision
// and reads or writes columns of the other (the BVH builder's sweep, the tracer's double
// surfaces into float columns, the pinhole camera's double rays, the scatter kernel's shadow
// contributions and throughputs, the arrivals' throughputs). Widening is exact; narrowing rounds to
// nearest, as a scalar cast does. For the per-ISA units, as simd/lanes.h.
#pragma once

#include "raylane/simd/lanes.h"

namespace raylane::simd {

// Float lanes widened (exactly) to double and stored: the low four at lo[0..3] and, with eight
// lanes, the high four at hi[0..3].
template <class A>
inline void store_widened(double* lo, double* hi, const Floats<A>& v) {
  if constexpr (kWidth<A> == 8) {
    _mm256_storeu_pd(lo, _mm256_cvtps_pd(_mm256_castps256_ps128(__m256(v))));
    _mm256_storeu_pd(hi, _mm256_cvtps_pd(_mm256_extractf128_ps(__m256(v), 1)));
  } else {
    static_assert(kWidth<A> == 4, "four or eight float lanes");
    (void)hi;
    _mm_storeu_pd(lo, _mm_cvtps_pd(__m128(v)));
    _mm_storeu_pd(lo + 2, _mm_cvtps_pd(_mm_movehl_ps(__m128(v), __m128(v))));
  }
}

// Double lanes rounded to nearest float (as a scalar cast rounds) and stored at p[0, W).
template <class A>
inline void store_narrowed(float* p, const Doubles<A>& v) {
  if constexpr (kDoubleWidth<A> == 8) {
    // Zero-masking with every lane kept: the plain intrinsic's undefined pass-through operand
    // trips GCC 12's -Wuninitialized wherever it inlines (simd/lanes.h, kAll16).
    _mm256_storeu_ps(p, _mm512_maskz_cvtpd_ps(__mmask8(0xff), __m512d(v)));
  } else if constexpr (kDoubleWidth<A> == 4) {
    _mm_storeu_ps(p, _mm256_cvtpd_ps(__m256d(v)));
  } else {
    static_assert(kDoubleWidth<A> == 2, "two, four or eight double lanes");
    _mm_storel_pi(reinterpret_cast<__m64*>(p), _mm_cvtpd_ps(__m128d(v)));
  }
}

// p[0, W) rounded to nearest float (as a scalar cast rounds), W the float lanes' count.
template <class A>
inline Floats<A> load_narrowed(const double* p) {
  if constexpr (kWidth<A> == 16) {
    const __m256 lo = _mm512_maskz_cvtpd_ps(__mmask8(0xff), _mm512_loadu_pd(p));
    const __m256 hi = _mm512_maskz_cvtpd_ps(__mmask8(0xff), _mm512_loadu_pd(p + 8));
    return Floats<A>(_mm512_castpd_ps(
        _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_castps_pd(lo)), _mm256_castps_pd(hi), 1)));
  } else if constexpr (kWidth<A> == 8) {
    return Floats<A>(_mm256_set_m128(_mm256_cvtpd_ps(_mm256_loadu_pd(p + 4)),
                                     _mm256_cvtpd_ps(_mm256_loadu_pd(p))));
  } else {
    static_assert(kWidth<A> == 4, "four, eight or sixteen float lanes");
    return Floats<A>(
        _mm_movelh_ps(_mm_cvtpd_ps(_mm_loadu_pd(p)), _mm_cvtpd_ps(_mm_loadu_pd(p + 2))));
  }
}

// Float lanes widened (exactly) to double and stored at p[0, W), W the float lanes' count.
template <class A>
inline void store_widened(double* p, const Floats<A>& v) {
  if constexpr (kWidth<A> == 16) {
    const __m512d bits = _mm512_castps_pd(__m512(v));
    _mm512_storeu_pd(p, _mm512_cvtps_pd(_mm256_castpd_ps(_mm512_castpd512_pd256(bits))));
    _mm512_storeu_pd(p + 8, _mm512_cvtps_pd(_mm256_castpd_ps(_mm512_extractf64x4_pd(bits, 1))));
  } else {
    store_widened<A>(p, p + 4, v);
  }
}

}  // namespace raylane::simd
