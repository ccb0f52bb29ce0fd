// Moving a batch's rows between columns in lanes: whether a batch's rows are one run of a
// column (then they load and store whole), and compaction, the step of a stream filter (the
// rows a mask keeps, packed to the front). For the per-ISA units, as simd/lanes.h.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "raylane/simd/lane_convert.h"
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

// Bits [0, n) of `bits` as n bytes, 0 or 1 each, at to[0, n) (n ≤ 16): a facing column written
// from a mask in one or two stores where a loop stored a byte at a time (a store per row, in
// a pass whose other stores are whole registers). Each group of eight bits is spread to the low bit
// of eight bytes by three shift-and-mask steps (each moves half of the remaining bits as far as
// they must go).
template <class A>
inline void store_flags(uint8_t* to, uint32_t bits, int n) {
  auto spread = [](uint64_t x) {
    x = (x | (x << 28)) & 0x0000000f0000000full;
    x = (x | (x << 14)) & 0x0003000300030003ull;
    return (x | (x << 7)) & 0x0101010101010101ull;
  };
  const uint64_t low = spread(bits & 0xffu);
  std::memcpy(to, &low, std::size_t(n < 8 ? n : 8));
  if (n > 8) {
    const uint64_t high = spread((bits >> 8) & 0xffu);
    std::memcpy(to + 8, &high, std::size_t(n - 8));
  }
}

// Compaction, a stream filter's step, on values in registers, for a filter fused into the
// kernel that computes them (the scatter kernel's queues): the lanes `keep` marks, packed to the
// front and stored whole at to[0, W). All W lanes are stored: those past the kept ones hold
// nothing of use (a filter writing at its kept count m ≤ the rows read so far stays within
// them). One mask's permutation is worked out once for every column it packs. AVX-512
// compresses in a register and stores it whole (vpcompressd's memory form is slow on AMD's
// cores); AVX2 permutes by the kept lanes' indices, which a 256-entry table holds 3 bits each;
// SSE4.2 copies every lane and advances past the kept ones (no branch on the data). Bits are
// moved as they are (floats, integers alike; NaN payloads and −0 too).
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
// SSE4.2: `lanes` values of `bytes` each, every one copied, the output advanced past the kept.
// (A template on A, unused, so that each instruction set's unit keeps its own copy, compiled
// with its own flags.)
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
class LanePacker {
 public:
  explicit LanePacker(uint32_t keep) : keep_(keep) {
    if constexpr (kWidth<A> == 8) {
      index_ = Ints<A>(_mm256_and_si256(
          _mm256_srlv_epi32(_mm256_set1_epi32(int(detail::kPackedLanes.entry[keep & 0xff])),
                            _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21)),
          _mm256_set1_epi32(7)));
    }
  }
  // How many lanes are kept: how far the destinations' counts advance.
  int count() const { return popcount<A>(keep_); }
  void store(float* to, const Floats<A>& v) const {
    if constexpr (kWidth<A> == 4) {
      alignas(16) float lanes[4];
      v.store_aligned(lanes);
      detail::compress_copy<A>(to, lanes, keep_, 4, 4);
    } else {
      packed(v).store_unaligned(to);
    }
  }
  void store(uint32_t* to, const Ints<A>& v) const {
    store(reinterpret_cast<float*>(to), xsimd::bitwise_cast<Floats<A>>(v));
  }
  // The kept lanes widened to double (exactly) and stored at to[0, W): packed as floats first,
  // then widened, so that the doubles need no permutation of their own.
  void store_widened(double* to, const Floats<A>& v) const {
    if constexpr (kWidth<A> == 4) {
      alignas(16) float lanes[4];
      v.store_aligned(lanes);
      for (int i = 0, out = 0; i < 4; ++i) {
        to[out] = double(lanes[i]);
        out += int((keep_ >> i) & 1u);
      }
    } else {
      simd::store_widened<A>(to, packed(v));
    }
  }

 private:
  // AVX2 and AVX-512: the kept lanes first, in a register.
  Floats<A> packed(const Floats<A>& v) const {
    if constexpr (kWidth<A> == 16) {
      return _mm512_maskz_compress_ps(__mmask16(keep_), __m512(v));
    } else {
      return _mm256_castsi256_ps(
          _mm256_permutevar8x32_epi32(_mm256_castps_si256(__m256(v)), __m256i(index_)));
    }
  }

  uint32_t keep_;
  Ints<A> index_{};  // AVX2: the permutation's lane indices
};

}  // namespace raylane::simd
