// sobol_group (src/render/samplers/sobol.cpp) in lanes, one pixel per lane, instantiated per instruction
// set by src/render/render_lanes_<isa>.cpp. Include from nowhere else. Every step is the scalar
// code's, on 32-bit unsigned lanes: the same values bit for bit (tests/render/sobol_test.cpp).
#pragma once

#include <type_traits>

#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sobol.h"
#include "raylane/simd/lanes.h"

namespace raylane::detail {

template <class A>
using U32 = simd::UInts<A>;

// Laine and Karras 2011 with Burley's constants, as scramble_reversed.
template <class A>
U32<A> scramble_reversed_lanes(U32<A> x, const U32<A>& seed) {
  x = x + seed;
  x = x ^ (x * U32<A>(0x6c50b47cu));
  x = x ^ (x * U32<A>(0xb82f1e52u));
  x = x ^ (x * U32<A>(0xc7afe638u));
  x = x ^ (x * U32<A>(0x8d22f6e6u));
  return x;
}

// Wellons's lowbias32, as hash32.
template <class A>
U32<A> hash32_lanes(U32<A> x) {
  x = x ^ (x >> 16);
  x = x * U32<A>(0x7feb352du);
  x = x ^ (x >> 15);
  x = x * U32<A>(0x846ca68bu);
  return x ^ (x >> 16);
}

// Dimension 1's matrix is Pascal's triangle mod 2 (its polynomial is x + 1): index bit k
// contributes C(k, j) mod 2 to bit j of the column m_k. By Lucas's theorem C(k, j) is odd
// exactly when j's bits are a subset of k's, so in the bit-reversed domain the point is the
// XOR over supersets of each bit position: five butterfly steps, one per bit of the position,
// instead of four table gathers (gathers are the lanes' slowest instructions).
template <class A>
U32<A> superset_xor_lanes(U32<A> x) {
  x = x ^ ((x >> 1) & U32<A>(0x55555555u));
  x = x ^ ((x >> 2) & U32<A>(0x33333333u));
  x = x ^ ((x >> 4) & U32<A>(0x0f0f0f0fu));
  x = x ^ ((x >> 8) & U32<A>(0x00ff00ffu));
  return x ^ ((x >> 16) & U32<A>(0x0000ffffu));
}

// Dimensions 2 and 3 by their byte tables, in the reversed domain.
template <class A>
U32<A> table_point_lanes(const U32<A>& r, uint32_t c) {
  const U32<A> byte(0xffu);
  const uint32_t* t = sobol_byte_tables() + 1024 * c;
  U32<A> b0 = r & byte, b1 = ((r >> 8) & byte) + U32<A>(256u);
  U32<A> b2 = ((r >> 16) & byte) + U32<A>(512u), b3 = (r >> 24) + U32<A>(768u);
  return simd::gather<A>(t, b0) ^ simd::gather<A>(t, b1) ^ simd::gather<A>(t, b2) ^
         simd::gather<A>(t, b3);
}

// Component c of the group from its Sobol point (reversed domain): scrambled by its own seed,
// reversed back, stored.
template <class A>
void store_component(SobolBatch& b, std::size_t i, uint32_t c, const U32<A>& point,
                     const U32<A>& seeds) {
  U32<A> v = scramble_reversed_lanes<A>(point, hash32_lanes<A>(seeds + U32<A>(c)));
  simd::reverse_bits<A>(v).store_unaligned(b.u[c].data() + i);
}

// The rows' group seeds, group_seed_of (mix64 of the pixel's seed and the group's salt) split
// into the index's scramble (low half) and the components' seed (high half). In 64-bit lanes
// where the instruction set multiplies them (AVX-512DQ's vpmullq); a row at a time elsewhere
// (AVX2 and SSE4.2 have no 64-bit low multiply).
template <class A>
void group_seeds(uint32_t group, SobolBatch& b) {
  const uint64_t salt = group_salt(group);
  if constexpr (std::is_base_of_v<xsimd::avx512dq, A>) {
    using U64 = xsimd::batch<uint64_t, A>;
    constexpr std::size_t W = U64::size;
    for (std::size_t i = 0; i < b.padded_size(); i += W) {
      // mix64's steps (render/samplers/rng.h), lane by lane.
      U64 z = (U64::load_unaligned(b.seed.data() + i) ^ U64(salt)) + U64(0x9e3779b97f4a7c15ull);
      z = (z ^ (z >> 30)) * U64(0xbf58476d1ce4e5b9ull);
      z = (z ^ (z >> 27)) * U64(0x94d049bb133111ebull);
      z = z ^ (z >> 31);
      simd::store_halves<A>(b.scramble.data() + i, b.component.data() + i, z);
    }
  } else {
    for (std::size_t i = 0; i < b.padded_size(); ++i) {
      const uint64_t g = mix64(b.seed[i] ^ salt);
      b.scramble[i] = uint32_t(g), b.component[i] = uint32_t(g >> 32);
    }
  }
}

// The groups' components in the set `which` (bit c: component c; 0 and 1 always): dimensions 2
// and 3 (the gathers) only if asked.
template <class A>
void sobol_groups_range(uint32_t reversed_index, uint32_t group, unsigned which, SobolBatch& b) {
  constexpr std::size_t W = simd::kWidth<A>;
  group_seeds<A>(group, b);
  for (std::size_t i = 0; i < b.padded_size(); i += W) {
    U32<A> scramble = U32<A>::load_unaligned(b.scramble.data() + i);
    U32<A> seeds = U32<A>::load_unaligned(b.component.data() + i);
    U32<A> r = scramble_reversed_lanes<A>(U32<A>(reversed_index), scramble);
    // Dimension 0 is the radical inverse: in the reversed domain, the reversed index itself.
    U32<A> radical = simd::reverse_bits<A>(r);
    store_component<A>(b, i, 0, radical, seeds);
    store_component<A>(b, i, 1, superset_xor_lanes<A>(radical), seeds);
    if (which & 4u) store_component<A>(b, i, 2, table_point_lanes<A>(r, 2), seeds);
    if (which & 8u) store_component<A>(b, i, 3, table_point_lanes<A>(r, 3), seeds);
  }
}

// The groups' components in `which` as numbers into the callers' columns (SobolNumbers): plain
// loops, which the compiler vectorises with this file's instruction set (the baseline build has
// no unsigned-to-double conversion in lanes). The expressions are sobol_group's, so the doubles
// are its own bit for bit and the floats unit_float's of them. (A template on A, though A is
// unused, so that each instruction set's unit keeps its own copy: one inline function would be
// one definition for the linker to pick.)
template <class A>
void sobol_numbers(unsigned which, const SobolBatch& b, const SobolNumbers& to) {
  const std::size_t n = b.size();
  for (std::size_t c = 0; c < 4; ++c) {
    if (!(which & (1u << c))) continue;
    const uint32_t* u = b.u[c].data();
    if (double* d = to.as_double[c])
      for (std::size_t r = 0; r < n; ++r)
        d[r] = u[r] * 0x1p-32;
    if (float* f = to.as_float[c])
      for (std::size_t r = 0; r < n; ++r) {
        // unit_float's value, spelled out: std::min would be an ordinary inline function
        // (docs/design.md, "SIMD and the instruction sets").
        const float v = float(u[r] * 0x1p-32);
        f[r] = kLargestBelowOne < v ? kLargestBelowOne : v;
      }
  }
}

}  // namespace raylane::detail
