// 64-bit unsigned lanes for the integer steps written once over their type (the Sobol groups'
// seeds: splitmix64_finaliser, render/samplers/rng.h), and their split into 32-bit halves. For
// the per-ISA units, as simd/lanes.h.
#pragma once

#include <cstddef>
#include <cstdint>

#include "raylane/simd/lanes.h"

namespace raylane::simd {

// 64-bit unsigned lanes split into their low halves at low[0, N) and high halves at
// high[0, N), N the lanes' count: AVX-512's truncating vpmovqd; AVX2 and SSE4.2 gather the
// halves by a permutation of their 32-bit lanes.
template <class A>
inline void store_halves(uint32_t* low, uint32_t* high, const xsimd::batch<uint64_t, A>& v) {
  constexpr std::size_t N = xsimd::batch<uint64_t, A>::size;
  if constexpr (N == 8) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(low), _mm512_cvtepi64_epi32(__m512i(v)));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(high),
                        _mm512_cvtepi64_epi32(_mm512_srli_epi64(__m512i(v), 32)));
  } else if constexpr (N == 4) {
    const __m256i halves =
        _mm256_permutevar8x32_epi32(__m256i(v), _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(low), _mm256_castsi256_si128(halves));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(high), _mm256_extracti128_si256(halves, 1));
  } else {
    static_assert(N == 2, "two, four or eight 64-bit lanes");
    const __m128i halves = _mm_shuffle_epi32(__m128i(v), _MM_SHUFFLE(3, 1, 2, 0));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(low), halves);
    _mm_storel_epi64(reinterpret_cast<__m128i*>(high), _mm_unpackhi_epi64(halves, halves));
  }
}

// 64-bit unsigned lanes whose arithmetic is uint64_t's, modulo 2^64, at every instruction set,
// for the integer steps written once over their type (splitmix64_finaliser,
// render/samplers/rng.h). The product keeps the low 64 bits: AVX-512DQ multiplies 64-bit lanes
// (vpmullq); AVX2 and SSE4.2 multiply only 32-bit halves into 64 bits (pmuludq), so there it is
// lo(a)·lo(b) + ((hi(a)·lo(b) + lo(a)·hi(b)) << 32), the hi·hi term falling past bit 63 (xsimd
// 8.1 multiplies such lanes one by one).
template <class A>
struct U64Lanes {
  using V = xsimd::batch<uint64_t, A>;
  V v;

  U64Lanes(const V& x) : v(x) {}  // NOLINT: lanes and their wrapper interchange freely
  explicit U64Lanes(uint64_t x) : v(x) {}
  friend U64Lanes operator+(const U64Lanes& a, const U64Lanes& b) { return a.v + b.v; }
  friend U64Lanes operator^(const U64Lanes& a, const U64Lanes& b) { return a.v ^ b.v; }
  friend U64Lanes operator>>(const U64Lanes& a, int shift) { return a.v >> shift; }
  friend U64Lanes operator*(const U64Lanes& a, const U64Lanes& b) {
    if constexpr (V::size == 8) {
      return V(_mm512_mullo_epi64(__m512i(a.v), __m512i(b.v)));
    } else if constexpr (V::size == 4) {
      const __m256i x = a.v, y = b.v;
      const __m256i cross = _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(x, 32), y),
                                             _mm256_mul_epu32(x, _mm256_srli_epi64(y, 32)));
      return V(_mm256_add_epi64(_mm256_mul_epu32(x, y), _mm256_slli_epi64(cross, 32)));
    } else {
      const __m128i x = a.v, y = b.v;
      const __m128i cross = _mm_add_epi64(_mm_mul_epu32(_mm_srli_epi64(x, 32), y),
                                          _mm_mul_epu32(x, _mm_srli_epi64(y, 32)));
      return V(_mm_add_epi64(_mm_mul_epu32(x, y), _mm_slli_epi64(cross, 32)));
    }
  }
};

// base[idx[k] · stride] in 64-bit lane k, for the lanes' N 32-bit indices at idx (each
// idx[k] · stride below 2^31: the gathers' indices are signed): one 64-bit gather on AVX2 and
// AVX-512, two loads on SSE4.2 (no gathers).
template <class A>
inline U64Lanes<A> gather_u64(const uint64_t* base, const uint32_t* idx, uint32_t stride) {
  using V = typename U64Lanes<A>::V;
  const long long* from = reinterpret_cast<const long long*>(base);
  if constexpr (V::size == 8) {
    const __m256i i = _mm256_mullo_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx)),
                                         _mm256_set1_epi32(int(stride)));
    return V(_mm512_i32gather_epi64(i, from, 8));
  } else if constexpr (V::size == 4) {
    const __m128i i = _mm_mullo_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(idx)),
                                      _mm_set1_epi32(int(stride)));
    return V(_mm256_i32gather_epi64(from, i, 8));
  } else {
    return V(
        _mm_set_epi64x(from[std::size_t(idx[1]) * stride], from[std::size_t(idx[0]) * stride]));
  }
}

// p[0, N) widened to the lanes' 64 bits (zero-extended).
template <class A>
inline U64Lanes<A> load_widened(const uint32_t* p) {
  using V = typename U64Lanes<A>::V;
  if constexpr (V::size == 8) {
    return V(_mm512_cvtepu32_epi64(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p))));
  } else if constexpr (V::size == 4) {
    return V(_mm256_cvtepu32_epi64(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))));
  } else {
    return V(_mm_cvtepu32_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p))));
  }
}

}  // namespace raylane::simd
