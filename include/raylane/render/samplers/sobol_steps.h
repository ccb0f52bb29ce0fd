// The Owen-scrambled Sobol sampler's steps (render/samplers/sobol.h), written once over the
// number type: U = uint32_t for sobol_group and sobol_point (src/render/samplers/sobol.cpp), U =
// 32-bit unsigned lanes for sobol_groups (src/render/samplers/sobol_lanes_impl.h, through
// simd/lane_numbers.h). The arithmetic is modulo 2^32, exact, so the two agree bit for bit by
// construction. Everything works in the bit-reversed domain, where the scrambles below are
// nested: a component needs one reversal, at its end.
#pragma once

#include <cstdint>

#include "raylane/core/numbers.h"
#include "raylane/render/samplers/sobol.h"

namespace raylane {

// A 32-bit integer hash with good avalanche (Wellons 2018, "Prospecting for hash functions",
// the constants of his "lowbias32"): seeds for the scrambles of one group's components.
template <class U>
U sobol_hash32(U x) {
  x = x ^ (x >> 16);
  x = x * U(0x7feb352du);
  x = x ^ (x >> 15);
  x = x * U(0x846ca68bu);
  return x ^ (x >> 16);
}

// Laine and Karras 2011 ("Stratified sampling for stochastic transparency") observed that
// x ↦ x ⊕ (x·even) and x ↦ x + seed change each bit by a function of the bits below it only;
// on the bit-reversed value that is a nested uniform scramble. The constants are Burley's
// (2020, "Practical Hash-based Owen Scrambling", §3), chosen for how well they mix.
template <class U>
U scramble_reversed(U x, const U& seed) {
  x = x + seed;
  x = x ^ (x * U(0x6c50b47cu));
  x = x ^ (x * U(0xb82f1e52u));
  x = x ^ (x * U(0xc7afe638u));
  x = x ^ (x * U(0x8d22f6e6u));
  return x;
}

// Dimension 1's matrix is Pascal's triangle mod 2 (its polynomial is x + 1): index bit k
// contributes C(k, j) mod 2 to bit j of the column m_k. By Lucas's theorem C(k, j) is odd
// exactly when j's bits are a subset of k's, so in the bit-reversed domain the point is the
// XOR over supersets of each bit position of the index: five butterfly steps, one per bit of
// the position, instead of four table lookups (gathers are the lanes' slowest instructions).
template <class U>
U superset_xor(U x) {
  x = x ^ ((x >> 1) & U(0x55555555u));
  x = x ^ ((x >> 2) & U(0x33333333u));
  x = x ^ ((x >> 4) & U(0x0f0f0f0fu));
  x = x ^ ((x >> 8) & U(0x00ff00ffu));
  return x ^ ((x >> 16) & U(0x0000ffffu));
}

// The generator-matrix product of dimension d = 2 or 3 over GF(2), in the reversed domain: the
// XOR of one table entry per chunk of the reversed index r. Lanes whose register permute reads
// Num<U>::kPermuteBits > 0 bits of an index look each chunk of that many bits up in one
// permute (detail::sobol_chunk_tables); the rest, scalar code among them, look each byte up in
// a 256-entry table (detail::sobol_byte_tables), a gather in lanes. The product is linear, so
// both give the same bits.
template <class U>
U reversed_table_point(const U& r, uint32_t d) {
  using O = Num<U>;
  constexpr int C = O::kPermuteBits;
  if constexpr (C > 0) {
    constexpr int kChunks = (32 + C - 1) / C, kEntries = 1 << C;
    const uint32_t* t = detail::sobol_chunk_tables(C) + kChunks * kEntries * (d - 2);
    U x = O::permute(t, r);  // the permute reads only the low C bits of each index
#pragma GCC unroll 16
    for (int j = 1; j < kChunks; ++j)
      x = x ^ O::permute(t + kEntries * j, r >> (C * j));
    return x;
  } else {
    const uint32_t* t = detail::sobol_byte_tables() + 1024 * (d - 2);
    const U byte(0xffu);
    const U b0 = r & byte, b1 = ((r >> 8) & byte) + U(256u);
    const U b2 = ((r >> 16) & byte) + U(512u), b3 = (r >> 24) + U(768u);
    return O::gather(t, b0) ^ O::gather(t, b1) ^ O::gather(t, b2) ^ O::gather(t, b3);
  }
}

// The bit-reversed Sobol point of dimension d = 0..3 for the bit-reversed index r. Dimension 0
// is the radical inverse, whose point is the reversed index: reversed, the index itself.
template <class U>
U reversed_sobol_point(const U& r, uint32_t d) {
  const U index = Num<U>::reverse_bits(r);
  if (d == 0) return index;
  if (d == 1) return superset_xor(index);
  return reversed_table_point(r, d);
}

// Component c of a group from its reversed Sobol point: scrambled by its own seed (a hash of
// the group's components' seed and c), then reversed into the 32 bits of the number.
template <class U>
U scrambled_component(const U& reversed_point, const U& component_seed, uint32_t c) {
  const U v = scramble_reversed(reversed_point, sobol_hash32(component_seed + U(c)));
  return Num<U>::reverse_bits(v);
}

// The components in the set `which` (bit c: component c; 0 and 1 always) of the group whose
// seeds are index_seed and component_seed, for the point index given bit-reversed:
// store(c, bits) gets component c's 32 bits, the number bits·2^-32 (sobol_unit). The index is
// shuffled per group first (a scramble of its bits is a permutation of every aligned block of
// 2^m indices), so groups are independent yet each block of 2^m samples is still the same net.
template <class U, class Store>
void sobol_group_bits(const U& reversed_index, const U& index_seed, const U& component_seed,
                      unsigned which, Store&& store) {
  const U r = scramble_reversed(reversed_index, index_seed);
  // reversed_sobol_point's dimensions, the index's reversal shared by 0 and 1.
  const U index = Num<U>::reverse_bits(r);
  store(0u, scrambled_component(index, component_seed, 0u));
  store(1u, scrambled_component(superset_xor(index), component_seed, 1u));
  if (which & 4u) store(2u, scrambled_component(reversed_table_point(r, 2), component_seed, 2u));
  if (which & 8u) store(3u, scrambled_component(reversed_table_point(r, 3), component_seed, 3u));
}

// unit_float(sobol_unit(bits)) without a double: bits·2^-32 rounded to float once, then kept
// below 1 as unit_float keeps it. The two 16-bit halves as floats, float(hi)·2^16 and
// float(lo), are exact, so their sum rounds once, to nearest, as the double's conversion does;
// the scaling by 2^-32 is exact. (Lanes convert only signed integers before AVX-512, and
// through double at half the width.) Tag: as sobol_unit's below, for the scalar instance.
template <class Tag = void, class U>
auto sobol_unit_float(const U& bits) {
  using F = typename Num<U>::Float;
  const F sum = Num<U>::to_float(bits >> 16) * F(65536.0f) + Num<U>::to_float(bits & U(0xffffu));
  const F f = sum * F(0x1p-32f), top(kLargestBelowOne);
  return Num<F>::select(top < f, top, f);
}

// A component's 32 bits as the number in [0, 1) they stand for, bits·2^-32 (exact in double).
// Tag: a per-ISA translation unit passes its instruction set, so that it keeps a copy of its
// own rather than emit one the linker could pick for the whole program (docs/design.md, "SIMD
// and the instruction sets": translation-unit hygiene); other callers leave it.
template <class Tag = void>
double sobol_unit(uint32_t bits) {
  return bits * 0x1p-32;
}

}  // namespace raylane
