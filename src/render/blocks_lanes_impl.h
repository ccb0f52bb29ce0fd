// blocks_of_paths (render_lanes.h) in lanes, instantiated per instruction set by
// src/render/render_lanes_<isa>.cpp. Include from nowhere else.
#pragma once

#include <cstddef>
#include <cstdint>

#include "raylane/simd/lanes.h"

namespace raylane::detail {

// The bit of each path's block (path >> shift, below 64) ORed into one word: a variable shift of
// 1 per lane into two 32-bit halves (VPSLLVD gives 0 for a count of 32 or more, so each lane sets
// its bit in the one half it falls in). SSE4.2 has no variable shift per lane: a scalar loop.
template <class A>
uint64_t blocks_of_paths_range(const uint32_t* path, std::size_t n, unsigned shift) {
  constexpr std::size_t W = std::size_t(simd::kWidth<A>);
  std::size_t i = 0;
  uint64_t bits = 0;
  if constexpr (W == 16) {
    __m512i lo = _mm512_setzero_si512(), hi = lo;
    const __m512i one = _mm512_set1_epi32(1), low_half = _mm512_set1_epi32(32);
    for (; i + W <= n; i += W) {
      const __m512i block = _mm512_srli_epi32(_mm512_loadu_si512(path + i), shift);
      lo = _mm512_or_si512(lo, _mm512_sllv_epi32(one, block));
      hi = _mm512_or_si512(hi, _mm512_sllv_epi32(one, _mm512_sub_epi32(block, low_half)));
    }
    bits = uint64_t(uint32_t(_mm512_reduce_or_epi32(lo))) |
           uint64_t(uint32_t(_mm512_reduce_or_epi32(hi))) << 32;
  } else if constexpr (W == 8) {
    __m256i lo = _mm256_setzero_si256(), hi = lo;
    const __m256i one = _mm256_set1_epi32(1), low_half = _mm256_set1_epi32(32);
    for (; i + W <= n; i += W) {
      const __m256i block = _mm256_srli_epi32(
          _mm256_loadu_si256(reinterpret_cast<const __m256i*>(path + i)), int(shift));
      lo = _mm256_or_si256(lo, _mm256_sllv_epi32(one, block));
      hi = _mm256_or_si256(hi, _mm256_sllv_epi32(one, _mm256_sub_epi32(block, low_half)));
    }
    alignas(32) uint32_t l[8], h[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(l), lo);
    _mm256_store_si256(reinterpret_cast<__m256i*>(h), hi);
    for (std::size_t k = 0; k < 8; ++k)
      bits |= uint64_t(l[k]) | uint64_t(h[k]) << 32;
  }
  for (; i < n; ++i)
    bits |= uint64_t(1) << (path[i] >> shift);
  return bits;
}

}  // namespace raylane::detail
