// Moving a batch's rows between columns in lanes: whether a batch's rows are one run of a
// column (then they load and store whole), and compaction, the step of a stream filter (the
// rows a mask keeps, packed to the front). For the per-ISA units, as simd/lanes.h.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "raylane/simd/lanes.h"

namespace raylane::simd {

// Rows [i, i + W) of three float columns (a batch's vector, x, y and z) as lanes, and back.
template <class A>
FloatVec3<A> load3(const std::array<std::vector<float>, 3>& c, std::size_t i) {
  return {load<A>(c[0].data() + i), load<A>(c[1].data() + i), load<A>(c[2].data() + i)};
}
template <class A>
void store3(std::array<std::vector<float>, 3>& c, std::size_t i, const FloatVec3<A>& v) {
  store<A>(c[0].data() + i, v.x), store<A>(c[1].data() + i, v.y), store<A>(c[2].data() + i, v.z);
}

// Whether rows[0, W) are one run, rows[k] = rows[0] + k: then a batch's columns load and
// store whole rather than row by row.
template <int W>
inline bool one_run(const uint32_t* rows) {
  bool run = true;
  for (int k = 1; k < W; ++k)
    run = run && rows[k] == rows[0] + uint32_t(k);
  return run;
}

// Compaction, a stream filter's step: the values at from[0, N) whose bit in `keep` is set,
// packed to the front and stored at to[0, N), N the lane count for values of their size
// (kWidth<A> for 4 bytes, kDoubleWidth<A> for 8). All N lanes are stored: those past the
// kept ones hold nothing of use (a filter writing at its kept count m ≤ the rows read so far
// stays within them). AVX-512 compresses in a register and stores it whole (vpcompressd's
// memory form is slow on AMD's cores); AVX2 permutes by the kept lanes' indices, which a
// 256-entry table holds 3 bits each; SSE4.2 copies every lane and advances past the kept ones
// (no branch on the data). Bytes are moved as they are (floats, integers alike).
namespace detail {
// Entry m: the indices of m's set bits in order, 3 bits each from bit 0. (A plain array: a
// std::array's operator[] would be an ordinary inline function emitted by the per-ISA units.)
struct PackedLanes {
  uint32_t entry[256];
};
inline constexpr PackedLanes kPackedLanes = [] {
  PackedLanes t{};
  for (uint32_t m = 0; m < 256; ++m)
    for (uint32_t i = 0, k = 0; i < 8; ++i)
      if (m & (1u << i)) t.entry[m] |= i << (3 * k++);
  return t;
}();
// AVX2: eight 32-bit lanes permuted so that the kept ones come first. (A template on A, unused,
// so that each instruction set's unit keeps its own copy, compiled with its own flags.)
template <class A>
inline __m256i compress8(__m256i v, uint32_t keep) {
  const __m256i idx =
      _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(int(kPackedLanes.entry[keep & 0xff])),
                                         _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21)),
                       _mm256_set1_epi32(7));
  return _mm256_permutevar8x32_epi32(v, idx);
}
// SSE4.2: `lanes` values of `bytes` each, every one copied, the output advanced past the kept.
template <class A>
inline void compress_copy(void* to, const void* from, uint32_t keep, int lanes, int bytes) {
  auto* out = static_cast<unsigned char*>(to);
  const auto* in = static_cast<const unsigned char*>(from);
  for (int i = 0; i < lanes; ++i) {
    std::memcpy(out, in + bytes * i, std::size_t(bytes));
    out += bytes * int((keep >> i) & 1u);
  }
}
}  // namespace detail

template <class A>
inline void store_compressed32(void* to, const void* from, uint32_t keep) {
  if constexpr (kWidth<A> == 16) {
    _mm512_storeu_si512(to, _mm512_maskz_compress_epi32(__mmask16(keep), _mm512_loadu_si512(from)));
  } else if constexpr (kWidth<A> == 8) {
    const __m256i v = _mm256_loadu_si256(static_cast<const __m256i*>(from));
    _mm256_storeu_si256(static_cast<__m256i*>(to), detail::compress8<A>(v, keep));
  } else {
    detail::compress_copy<A>(to, from, keep, kWidth<A>, 4);
  }
}
template <class A>
inline void store_compressed64(void* to, const void* from, uint32_t keep) {
  if constexpr (kDoubleWidth<A> == 8) {
    _mm512_storeu_si512(to, _mm512_maskz_compress_epi64(__mmask8(keep), _mm512_loadu_si512(from)));
  } else if constexpr (kDoubleWidth<A> == 4) {
    // Four 64-bit lanes as eight 32-bit ones: each kept lane keeps both its halves (bit i of
    // keep becomes bits 2i and 2i + 1).
    const uint32_t pairs =
        (keep & 1u) * 3u | (keep & 2u) * 6u | (keep & 4u) * 12u | (keep & 8u) * 24u;
    const __m256i v = _mm256_loadu_si256(static_cast<const __m256i*>(from));
    _mm256_storeu_si256(static_cast<__m256i*>(to), detail::compress8<A>(v, pairs));
  } else {
    detail::compress_copy<A>(to, from, keep, kDoubleWidth<A>, 8);
  }
}

}  // namespace raylane::simd
