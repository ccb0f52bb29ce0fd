// The only header that includes xsimd: lane types for float, double and int32 and the few
// operations the kernels need, for any instruction set A (SSE4.2: 4 lanes, AVX2: 8, AVX-512: 16).
// Include it only from the per-ISA translation units (src/trace/simd_tracer_*.cpp,
// src/render/render_lanes_*.cpp, src/bvh/bin_lanes_*.cpp) and the templates they
// instantiate; baseline code talks to them through simd/isa.h or their own headers.
// Masks: combine them with &, | and ! only. In xsimd 8.1, `^` of two AVX-512 masks and `!=` of
// two SSE double masks compute their OR (found by tests/trace/tracer_test.cpp). Where the sign
// of a zero or a NaN must be the scalar code's, negate with simd::negate, not unary minus.
#pragma once

#include <immintrin.h>

#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>
#include <xsimd/xsimd.hpp>

namespace raylane::simd {

template <class A>
using Floats = xsimd::batch<float, A>;
template <class A>
using Ints = xsimd::batch<int32_t, A>;
template <class A>
using Mask = xsimd::batch_bool<float, A>;
template <class A>
inline constexpr int kWidth = int(Floats<A>::size);

// Lane i of the mask as bit i.
template <class A>
inline uint32_t bits(const Mask<A>& m) {
  if constexpr (kWidth<A> == 16) {
    return uint32_t(__mmask16(m));
  } else if constexpr (kWidth<A> == 8) {
    return uint32_t(_mm256_movemask_ps(__m256(m)));
  } else {
    return uint32_t(_mm_movemask_ps(__m128(m)));
  }
}

template <class A>
inline bool any(const Mask<A>& m) {
  return xsimd::any(m);
}
template <class A>
inline bool none(const Mask<A>& m) {
  return !xsimd::any(m);
}
template <class A>
inline Floats<A> select(const Mask<A>& m, const Floats<A>& a, const Floats<A>& b) {
  return xsimd::select(m, a, b);
}
template <class A>
inline Ints<A> select(const Mask<A>& m, const Ints<A>& a, const Ints<A>& b) {
  return xsimd::select(xsimd::bool_cast(m), a, b);
}
// Lanes where a == b, as a mask over float lanes.
template <class A>
inline Mask<A> equal(const Ints<A>& a, const Ints<A>& b) {
  return xsimd::bool_cast(a == b);
}

// GCC 12's _mm512_max_ps/_mm512_min_ps pass _mm512_undefined_ps(), a self-initialised value
// that -Wuninitialized flags once inlined deep enough; the zero-masking forms with every lane
// on are the same instruction without it.
inline constexpr __mmask16 kAll16 = 0xFFFF;

// NaN-keeping running extrema: x > acc ? x : acc (and x < acc ? x : acc), so where x is NaN
// (or not better) the accumulator is kept. The operand order is the contract (docs/hard-cases.md
// N2). x86's MAXPS/MINPS compute exactly this, returning the second operand when either is
// NaN or both are zeros (Intel SDM vol. 2, MAXPS), so the instruction is named here rather
// than left to xsimd::max, whose operand order is unspecified: one instruction instead of a
// compare and a blend, on the critical path of every node test.
template <class A>
inline Floats<A> max_keep(const Floats<A>& x, const Floats<A>& acc) {
  if constexpr (kWidth<A> == 16) {
    return Floats<A>(_mm512_maskz_max_ps(kAll16, __m512(x), __m512(acc)));
  } else if constexpr (kWidth<A> == 8) {
    return Floats<A>(_mm256_max_ps(__m256(x), __m256(acc)));
  } else {
    return Floats<A>(_mm_max_ps(__m128(x), __m128(acc)));
  }
}
template <class A>
inline Floats<A> min_keep(const Floats<A>& x, const Floats<A>& acc) {
  if constexpr (kWidth<A> == 16) {
    return Floats<A>(_mm512_maskz_min_ps(kAll16, __m512(x), __m512(acc)));
  } else if constexpr (kWidth<A> == 8) {
    return Floats<A>(_mm256_min_ps(__m256(x), __m256(acc)));
  } else {
    return Floats<A>(_mm_min_ps(__m128(x), __m128(acc)));
  }
}

// The smallest lane of x (xsimd 8.1 has no horizontal minimum): halves folded onto each
// other with MINPS. Contract: no lane is NaN (MINPS would then answer by operand order).
template <class A>
inline float reduce_min(const Floats<A>& x) {
  __m128 m;
  if constexpr (kWidth<A> == 16) {
    __m256 lo = _mm512_castps512_ps256(__m512(x));
    __m256 hi = _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(__m512(x)), 1));
    __m256 m8 = _mm256_min_ps(lo, hi);
    m = _mm_min_ps(_mm256_castps256_ps128(m8), _mm256_extractf128_ps(m8, 1));
  } else if constexpr (kWidth<A> == 8) {
    m = _mm_min_ps(_mm256_castps256_ps128(__m256(x)), _mm256_extractf128_ps(__m256(x), 1));
  } else {
    m = __m128(x);
  }
  m = _mm_min_ps(m, _mm_movehl_ps(m, m));
  m = _mm_min_ss(m, _mm_shuffle_ps(m, m, 1));
  return _mm_cvtss_f32(m);
}

template <class A>
inline Floats<A> load(const float* p) {
  return Floats<A>::load_unaligned(p);
}
template <class A>
inline Ints<A> load(const int32_t* p) {
  return Ints<A>::load_unaligned(p);
}
template <class A>
inline void store(float* p, const Floats<A>& v) {
  v.store_unaligned(p);
}
template <class A>
inline void store(int32_t* p, const Ints<A>& v) {
  v.store_unaligned(p);
}

// Lanes whose index is below n: the active mask of a partly filled packet.
template <class A>
inline Mask<A> first_lanes(int n) {
  alignas(64) float idx[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  return load<A>(idx) < Floats<A>(float(n));
}

// p[0], …, p[n − 1] into the first n lanes (n < W), zeros after; nothing past p + n is read.
// AVX2 and AVX-512 mask the load (masked-out lanes never fault); SSE4.2 has no masked
// load, so it copies.
template <class A>
inline Floats<A> load_first(const float* p, int n) {
  if constexpr (kWidth<A> == 16) {
    return Floats<A>(_mm512_maskz_loadu_ps(__mmask16((1u << n) - 1), p));
  } else if constexpr (kWidth<A> == 8) {
    alignas(32) static constexpr int32_t kOn[16] = {-1, -1, -1, -1, -1, -1, -1, -1,
                                                    0,  0,  0,  0,  0,  0,  0,  0};
    __m256i mask = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kOn + 8 - n));
    return Floats<A>(_mm256_maskload_ps(p, mask));
  } else {
    alignas(16) float tail[4] = {};
    for (int k = 0; k < n; ++k)
      tail[k] = p[k];
    return Floats<A>::load_aligned(tail);
  }
}

template <class A>
using UInts = xsimd::batch<uint32_t, A>;

// base[idx[i]] per lane: the gather instructions named directly (xsimd 8.1's gather for a
// float or int batch indexed by int32 fell back to one insert per lane on AVX-512 in the
// render's profile); SSE4.2 has none, so it loads lane by lane. AVX-512's are the masked forms
// with every lane on, for the reason max_keep gives.
template <class A>
inline Floats<A> gather(const float* base, const Ints<A>& idx) {
  if constexpr (kWidth<A> == 16) {
    return Floats<A>(_mm512_mask_i32gather_ps(_mm512_setzero_ps(), kAll16, __m512i(idx), base, 4));
  } else if constexpr (kWidth<A> == 8) {
    return Floats<A>(_mm256_i32gather_ps(base, __m256i(idx), 4));
  } else {
    alignas(16) int32_t i[4];
    alignas(16) float v[4];
    idx.store_aligned(i);
    for (int k = 0; k < 4; ++k)
      v[k] = base[i[k]];
    return Floats<A>::load_aligned(v);
  }
}
template <class A>
inline UInts<A> gather(const uint32_t* base, const UInts<A>& idx) {
  if constexpr (kWidth<A> == 16) {
    return UInts<A>(
        _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), kAll16, __m512i(idx), base, 4));
  } else if constexpr (kWidth<A> == 8) {
    return UInts<A>(_mm256_i32gather_epi32(reinterpret_cast<const int*>(base), __m256i(idx), 4));
  } else {
    alignas(16) uint32_t i[4], v[4];
    idx.store_aligned(i);
    for (int k = 0; k < 4; ++k)
      v[k] = base[i[k]];
    return UInts<A>::load_aligned(v);
  }
}

// Each lane's 32 bits in reverse order, by byte shuffles: the bytes swapped, then each byte's
// two nibbles looked up reversed in 16-byte tables (pshufb, which SSSE3 has and so every
// instruction set here) — 7 instructions where the shift-and-mask butterflies take 19. The
// 256- and 512-bit shuffles work within 128-bit blocks, so the tables and the swap repeat per
// block.
namespace detail {
// Byte k of the result comes from byte kSwap[k] of the lane: 3 2 1 0 per 32-bit lane.
inline __m128i byte_swap_order() {
  return _mm_setr_epi8(3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12);
}
// The low nibble n reversed into the byte's high half, and the high nibble reversed into its low.
inline __m128i low_nibble_reversed() {
  return _mm_setr_epi8(0x00, char(0x80), 0x40, char(0xc0), 0x20, char(0xa0), 0x60, char(0xe0), 0x10,
                       char(0x90), 0x50, char(0xd0), 0x30, char(0xb0), 0x70, char(0xf0));
}
inline __m128i high_nibble_reversed() {
  return _mm_setr_epi8(0x0, 0x8, 0x4, 0xc, 0x2, 0xa, 0x6, 0xe, 0x1, 0x9, 0x5, 0xd, 0x3, 0xb, 0x7,
                       0xf);
}
}  // namespace detail

template <class A>
inline UInts<A> reverse_bits(const UInts<A>& x) {
  if constexpr (kWidth<A> == 16) {
    const __m512i swapped = _mm512_shuffle_epi8(
        __m512i(x), _mm512_maskz_broadcast_i32x4(kAll16, detail::byte_swap_order()));
    const __m512i nibble = _mm512_set1_epi8(0x0f);
    const __m512i lo = _mm512_and_si512(swapped, nibble);
    const __m512i hi = _mm512_and_si512(_mm512_srli_epi32(swapped, 4), nibble);
    return UInts<A>(_mm512_or_si512(
        _mm512_shuffle_epi8(_mm512_maskz_broadcast_i32x4(kAll16, detail::low_nibble_reversed()),
                            lo),
        _mm512_shuffle_epi8(_mm512_maskz_broadcast_i32x4(kAll16, detail::high_nibble_reversed()),
                            hi)));
  } else if constexpr (kWidth<A> == 8) {
    const __m256i swapped =
        _mm256_shuffle_epi8(__m256i(x), _mm256_broadcastsi128_si256(detail::byte_swap_order()));
    const __m256i nibble = _mm256_set1_epi8(0x0f);
    const __m256i lo = _mm256_and_si256(swapped, nibble);
    const __m256i hi = _mm256_and_si256(_mm256_srli_epi32(swapped, 4), nibble);
    return UInts<A>(_mm256_or_si256(
        _mm256_shuffle_epi8(_mm256_broadcastsi128_si256(detail::low_nibble_reversed()), lo),
        _mm256_shuffle_epi8(_mm256_broadcastsi128_si256(detail::high_nibble_reversed()), hi)));
  } else {
    const __m128i swapped = _mm_shuffle_epi8(__m128i(x), detail::byte_swap_order());
    const __m128i nibble = _mm_set1_epi8(0x0f);
    const __m128i lo = _mm_and_si128(swapped, nibble);
    const __m128i hi = _mm_and_si128(_mm_srli_epi32(swapped, 4), nibble);
    return UInts<A>(_mm_or_si128(_mm_shuffle_epi8(detail::low_nibble_reversed(), lo),
                                 _mm_shuffle_epi8(detail::high_nibble_reversed(), hi)));
  }
}

// 1 << b in each lane, 0 where b is 32 or more: AVX2's and AVX-512's variable shifts give 0
// there by definition (C++'s shift would be undefined); SSE4.2 has none, so lane by lane.
template <class A>
inline UInts<A> bit_of(const UInts<A>& b) {
  if constexpr (kWidth<A> == 16) {
    return UInts<A>(_mm512_sllv_epi32(_mm512_set1_epi32(1), __m512i(b)));
  } else if constexpr (kWidth<A> == 8) {
    return UInts<A>(_mm256_sllv_epi32(_mm256_set1_epi32(1), __m256i(b)));
  } else {
    alignas(16) uint32_t lanes[4];
    b.store_aligned(lanes);
    for (uint32_t& x : lanes)
      x = x < 32 ? 1u << x : 0u;
    return UInts<A>::load_aligned(lanes);
  }
}

// -x exactly, the sign bit flipped (as the scalar minus does): xsimd 8.1's unary minus computes
// 0 − x on AVX-512, which leaves +0 at +0 and a NaN's sign as it was.
template <class B>
inline B negate(const B& x) {
  static_assert(std::is_floating_point_v<typename B::value_type>, "float or double lanes");
  return x ^ B(typename B::value_type(-0.0));
}

template <class A>
using Doubles = xsimd::batch<double, A>;
template <class A>
inline constexpr int kDoubleWidth = int(Doubles<A>::size);

// Lane i of a double mask as bit i.
template <class A>
inline uint32_t bits(const xsimd::batch_bool<double, A>& m) {
  if constexpr (kDoubleWidth<A> == 8) {
    return uint32_t(__mmask8(m));
  } else if constexpr (kDoubleWidth<A> == 4) {
    return uint32_t(_mm256_movemask_pd(__m256d(m)));
  } else {
    return uint32_t(_mm_movemask_pd(__m128d(m)));
  }
}

// Three lanes of one number type, B a batch of floats or of doubles: a point or a direction
// per lane. The code base's one lane vector (FloatVec3 in the BSDF's float lanes, DoubleVec3 in
// the surfaces, lights and the steps after the BSDF); the scalar vectors are GLM's
// (core/vec_math.h).
template <class B>
struct LaneVec3 {
  B x, y, z;
};
template <class A>
using FloatVec3 = LaneVec3<Floats<A>>;
template <class A>
using DoubleVec3 = LaneVec3<Doubles<A>>;

template <class B>
LaneVec3<B> operator+(const LaneVec3<B>& a, const LaneVec3<B>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class B>
LaneVec3<B> operator-(const LaneVec3<B>& a, const LaneVec3<B>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class B>
LaneVec3<B> operator*(const LaneVec3<B>& a, const B& s) {
  return {a.x * s, a.y * s, a.z * s};
}

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited" (core/warps.h's Frame, in its
// order): the local direction v = (x, y, z) around the unit normal n, to world.
template <class B>
[[gnu::always_inline]] inline LaneVec3<B> to_world(const LaneVec3<B>& n, const LaneVec3<B>& v) {
  using T = typename B::value_type;
  const B one(T(1));
  const B sign = xsimd::copysign(one, n.z);
  const B a = B(T(-1)) / (sign + n.z);
  const B b = n.x * n.y * a;
  const LaneVec3<B> s{one + sign * n.x * n.x * a, sign * b, -sign * n.x};
  const LaneVec3<B> t{b, sign + n.y * n.y * a, negate(n.y)};  // −0 for n.y = +0, as scalar
  return s * v.x + t * v.y + n * v.z;
}

// col[rows[0]], …, col[rows[W − 1]] widened to double (exactly): a table column read at one
// row per lane, for code that runs once per hit rather than per node. The gather instructions
// (rows below 2^31): filling an array and loading it stalled on store forwarding.
template <class A>
inline Doubles<A> load_rows(const float* col, const uint32_t* rows) {
  if constexpr (kDoubleWidth<A> == 8) {
    const __m256i idx = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(rows));
    return Doubles<A>(
        _mm512_maskz_cvtps_pd(__mmask8(0xFF), _mm256_i32gather_ps(col, idx, 4)));  // see kAll16
  } else if constexpr (kDoubleWidth<A> == 4) {
    const __m128i idx = _mm_loadu_si128(reinterpret_cast<const __m128i*>(rows));
    return Doubles<A>(_mm256_cvtps_pd(_mm_i32gather_ps(col, idx, 4)));
  } else {  // SSE4.2 has no gathers: two loads and a widening
    return Doubles<A>(_mm_cvtps_pd(_mm_setr_ps(col[rows[0]], col[rows[1]], 0.0f, 0.0f)));
  }
}
template <class A>
inline Doubles<A> load_rows(const std::vector<float>& col, const uint32_t* rows) {
  return load_rows<A>(col.data(), rows);
}

// The square root (IEEE, correctly rounded) of double lanes; on AVX-512 the zero-masking form
// with every lane on, for the reason given at kAll16.
template <class A>
inline Doubles<A> sqrt(const Doubles<A>& x) {
  if constexpr (kDoubleWidth<A> == 8) {
    return Doubles<A>(_mm512_maskz_sqrt_pd(__mmask8(0xFF), __m512d(x)));
  } else {
    return xsimd::sqrt(x);
  }
}
// The same for float lanes.
template <class A>
inline Floats<A> sqrt(const Floats<A>& x) {
  if constexpr (kWidth<A> == 16) {
    return Floats<A>(_mm512_maskz_sqrt_ps(kAll16, __m512(x)));
  } else {
    return xsimd::sqrt(x);
  }
}

// Eight double lanes held as 8 / kDoubleWidth<A> registers, lanes 0-3 read from left[0..3]
// and lanes 4-7 from right[0..3]: register j of them (the BVH builder's SAH sweep runs two
// rows of four side by side). AVX-512 joins the two halves in one register.
template <class A>
inline Doubles<A> load_pack(const double* left, const double* right, int j) {
  if constexpr (kDoubleWidth<A> == 8) {
    return Doubles<A>(_mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_loadu_pd(left)),
                                         _mm256_loadu_pd(right), 1));
  } else {
    const int lane = j * kDoubleWidth<A>;
    return Doubles<A>::load_unaligned(lane < 4 ? left + lane : right + lane - 4);
  }
}
template <class A>
inline void store_pack(double* left, double* right, int j, const Doubles<A>& v) {
  if constexpr (kDoubleWidth<A> == 8) {
    // The zero-masking forms, for the reason given at kAll16 (GCC 12 casts by extracting too).
    _mm256_storeu_pd(left, _mm512_maskz_extractf64x4_pd(__mmask8(0xF), __m512d(v), 0));
    _mm256_storeu_pd(right, _mm512_maskz_extractf64x4_pd(__mmask8(0xF), __m512d(v), 1));
  } else {
    const int lane = j * kDoubleWidth<A>;
    v.store_unaligned(lane < 4 ? left + lane : right + lane - 4);
  }
}

// The BVH builder's boxes as [lo, −hi] in eight float lanes (src/bvh/box_lanes.h): the two
// 128-bit halves of v swapped, [v4..v7, v0..v3].
template <class A>
inline Floats<A> swap_halves(const Floats<A>& v) {
  static_assert(kWidth<A> == 8, "eight float lanes");
  return Floats<A>(_mm256_permute2f128_ps(__m256(v), __m256(v), 1));
}

// Four rows of four floats transposed in place within each 128-bit half of A's registers (four
// or eight float lanes): lane k of r_j becomes lane j of r_k, in each half alike. Intel's
// _MM_TRANSPOSE4_PS (xmmintrin.h) steps: unpack the floats in pairs, then the pairs as doubles.
template <class A>
inline void transpose4(Floats<A>& r0, Floats<A>& r1, Floats<A>& r2, Floats<A>& r3) {
  if constexpr (kWidth<A> == 8) {
    __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpacklo_ps(r2, r3);
    __m256 t2 = _mm256_unpackhi_ps(r0, r1), t3 = _mm256_unpackhi_ps(r2, r3);
    auto pd = [](__m256 x) { return _mm256_castps_pd(x); };
    r0 = Floats<A>(_mm256_castpd_ps(_mm256_unpacklo_pd(pd(t0), pd(t1))));
    r1 = Floats<A>(_mm256_castpd_ps(_mm256_unpackhi_pd(pd(t0), pd(t1))));
    r2 = Floats<A>(_mm256_castpd_ps(_mm256_unpacklo_pd(pd(t2), pd(t3))));
    r3 = Floats<A>(_mm256_castpd_ps(_mm256_unpackhi_pd(pd(t2), pd(t3))));
  } else {
    static_assert(kWidth<A> == 4, "four or eight float lanes");
    __m128 t0 = _mm_unpacklo_ps(r0, r1), t1 = _mm_unpacklo_ps(r2, r3);
    __m128 t2 = _mm_unpackhi_ps(r0, r1), t3 = _mm_unpackhi_ps(r2, r3);
    r0 = Floats<A>(_mm_movelh_ps(t0, t1)), r1 = Floats<A>(_mm_movehl_ps(t1, t0));
    r2 = Floats<A>(_mm_movelh_ps(t2, t3)), r3 = Floats<A>(_mm_movehl_ps(t3, t2));
  }
}

// The number of set bits (POPCNT: SSE4.2 and later have it), not std::popcount, an ordinary
// inline function the per-ISA units would each emit.
template <class A>
inline int popcount(uint32_t x) {
  return _mm_popcnt_u32(x);
}

// signbit per lane, for ±0 as well as any other value (copysign carries the sign bit alone).
template <class A>
inline xsimd::batch_bool<double, A> sign_bit(const Doubles<A>& v) {
  return xsimd::copysign(Doubles<A>(1.0), v) < Doubles<A>(0.0);
}

// 0, 1, …, W − 1.
template <class A>
inline Ints<A> lane_index() {
  alignas(64) int32_t idx[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  return load<A>(idx);
}

// a·b + c with ONE rounding where the hardware has FMA. xsimd 8.1 has no fused fma for
// AVX-512 (it falls back to a·b + c, which GCC contracts in some places and not others), and
// a half-fused difference of products loses its exact sign and opens cracks between triangles
// (docs/hard-cases.md T2; found by the leak test). So the instruction is named here. SSE4.2 has no
// FMA: there a·b + c is two roundings, and the difference of products becomes the plain
// a·b − c·d, which is exactly antisymmetric, hence watertight too.
template <class A>
inline Floats<A> fma(const Floats<A>& a, const Floats<A>& b, const Floats<A>& c) {
  if constexpr (kWidth<A> == 16) {
    return Floats<A>(_mm512_fmadd_ps(__m512(a), __m512(b), __m512(c)));
  } else if constexpr (kWidth<A> == 8) {
    return Floats<A>(_mm256_fmadd_ps(__m256(a), __m256(b), __m256(c)));
  } else {
    return a * b + c;
  }
}

}  // namespace raylane::simd
