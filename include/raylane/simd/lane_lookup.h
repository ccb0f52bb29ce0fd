// Reading a short column at one row per lane: a scene's materials (a dozen in the course scene)
// are read by every lane row's material index several times per bounce. A gather loads lane by
// lane (sixteen loads' worth of work on AVX-512, the lanes' slowest instruction); a column that
// fits in one or two registers is loaded whole instead and read by a register permute, one
// instruction per register (Intel's intrinsics guide: VPERMPS, VPERMT2PS). For the per-ISA
// units, as simd/lanes.h.
#pragma once

#include <cstddef>
#include <cstdint>

#include "raylane/simd/lane_rows.h"
#include "raylane/simd/lanes.h"

namespace raylane::simd {

// col[idx[i]] per lane, for a column of n floats and each idx[i] in [0, n): exactly what
// gather<A>(col, idx) answers. Columns of up to 2·kWidth<A> floats are permuted (AVX-512,
// AVX2); longer ones, and SSE4.2 (no variable float permute across its four lanes that beats
// its lane-by-lane loads), gather. `readable` is how many floats from col may be read (n
// unless the column is padded): where it covers whole registers they load plainly, else their
// loads are masked at n.
template <class A>
[[gnu::always_inline]] inline Floats<A> lookup(const float* col, std::size_t n, const Ints<A>& idx,
                                               std::size_t readable = 0) {
  constexpr std::size_t W = std::size_t(kWidth<A>);
  if constexpr (W == 16) {
    if (n <= W)  // one register: one permute
      return Floats<A>(_mm512_permutexvar_ps(
          __m512i(idx), __m512(readable >= W ? load<A>(col) : load_first<A>(col, int(n)))));
    if (n <= 2 * W) {
      const __m512 high(readable >= 2 * W ? load<A>(col + W) : load_first<A>(col + W, int(n - W)));
      // Bit 4 of each index picks the register, bits 0-3 the lane.
      return Floats<A>(_mm512_permutex2var_ps(__m512(load<A>(col)), __m512i(idx), high));
    }
  } else if constexpr (W == 8) {
    if (n <= W)  // one register: one permute (the course scene's spheres and boxes)
      return Floats<A>(_mm256_permutevar8x32_ps(
          __m256(readable >= W ? load<A>(col) : load_first<A>(col, int(n))), __m256i(idx)));
    if (n <= 2 * W) {
      const __m256 high(readable >= 2 * W ? load<A>(col + W) : load_first<A>(col + W, int(n - W)));
      // VPERMPS reads bits 0-2 of each index; lanes whose index is 8 or more take the high one.
      const __m256 from_low = _mm256_permutevar8x32_ps(__m256(load<A>(col)), __m256i(idx));
      const __m256 from_high = _mm256_permutevar8x32_ps(high, __m256i(idx));
      const __m256i in_high = _mm256_cmpgt_epi32(__m256i(idx), _mm256_set1_epi32(int32_t(W) - 1));
      return Floats<A>(_mm256_blendv_ps(from_low, from_high, _mm256_castsi256_ps(in_high)));
    }
  }
  return gather<A>(col, idx);
}

// How many low bits of each index a one-register permute of 32-bit words reads: 4 over
// AVX-512's 16 lanes, 3 over AVX2's 8 (VPERMD ignores the rest); 0 for SSE4.2, which has no
// variable permute of words across its register.
template <class A>
inline constexpr int kPermuteIndexBits = kWidth<A> == 16  ? 4
                                         : kWidth<A> == 8 ? 3
                                                          : 0;

// table[idx[i] mod kWidth<A>] per lane by one permute, the index's higher bits ignored: a table
// of one register, 64-byte aligned (AVX2 and AVX-512 only: kPermuteIndexBits<A> > 0).
template <class A>
[[gnu::always_inline]] inline UInts<A> permute_words(const uint32_t* table, const UInts<A>& idx) {
  static_assert(kPermuteIndexBits<A> > 0, "no word permute at this width");
  const UInts<A> words = UInts<A>::load_aligned(table);
  if constexpr (kWidth<A> == 16) {
    return UInts<A>(_mm512_permutexvar_epi32(__m512i(idx), __m512i(words)));
  } else {
    return UInts<A>(_mm256_permutevar8x32_epi32(__m256i(words), __m256i(idx)));
  }
}

// Rows of a long column (a stream's rays) read at one row per lane, for a batch whose rows lie
// close together: the render's lane rows are its rays in order with a few skipped (misses,
// emitters, rows shaded in double), so a batch that is not one run mostly spans less than two
// registers' rows. Such a batch reads that window whole and permutes (lookup); one run loads
// straight; any other gathers.
template <class A>
class RowReader {
 public:
  explicit RowReader(const uint32_t* rows) {
    constexpr int W = kWidth<A>;
    idx_ = load<A>(reinterpret_cast<const int32_t*>(rows));
    lo_ = rows[0];
    // One run, the common batch, by one compare of the whole register: the scalar scan of the
    // rows that also found the window cost every batch a compare, a min and a max per row.
    // Rows are ray indices, below 2^31, so the sums do not wrap.
    const Ints<A> run = Ints<A>(int32_t(lo_)) + lane_index<A>();
    if (bits<A>(equal<A>(idx_, run)) == (1u << W) - 1) {
      span_ = std::size_t(W), way_ = Way::kRun;
      return;
    }
    uint32_t lo = rows[0], hi = rows[0];
    for (int k = 1; k < W; ++k)
      lo = rows[k] < lo ? rows[k] : lo, hi = rows[k] > hi ? rows[k] : hi;
    lo_ = lo, span_ = std::size_t(hi - lo) + 1;
    way_ = span_ <= std::size_t(2 * W) ? Way::kWindow : Way::kGather;
    if (way_ == Way::kWindow) idx_ = idx_ - Ints<A>(int32_t(lo));
  }
  // col[rows[k]] in lane k.
  Floats<A> read(const float* col) const {
    switch (way_) {
      case Way::kRun:
        return load<A>(col + lo_);
      case Way::kWindow:
        return lookup<A>(col + lo_, span_, idx_);
      default:
        return gather<A>(col, idx_);
    }
  }

 private:
  enum class Way { kRun, kWindow, kGather };
  Ints<A> idx_;  // the rows, or in a window their offsets from its first
  uint32_t lo_;
  std::size_t span_;
  Way way_;
};

}  // namespace raylane::simd
