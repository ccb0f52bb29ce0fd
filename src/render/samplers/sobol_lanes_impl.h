// sobol_group (src/render/samplers/sobol.cpp) in lanes, one pixel per lane, instantiated per
// instruction set by src/render/render_lanes_<isa>.cpp. Include from nowhere else. The steps are
// sobol_group's own text (render/samplers/sobol_steps.h) on 32-bit unsigned lanes: the same
// values bit for bit (tests/render/sobol_test.cpp).
#pragma once

#include <type_traits>

#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sobol.h"
#include "raylane/render/samplers/sobol_steps.h"
#include "raylane/simd/lane_numbers.h"
#include "raylane/simd/lanes.h"

namespace raylane::detail {

template <class A>
using U32 = simd::UInts<A>;

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
      const U64 z = splitmix64_finaliser(U64::load_unaligned(b.seed.data() + i) ^ U64(salt));
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
    sobol_group_bits(
        U32<A>(reversed_index), scramble, seeds, which,
        [&](uint32_t c, const U32<A>& bits) { bits.store_unaligned(b.u[c].data() + i); });
  }
}

// The groups' components in `which` as numbers into the callers' columns (SobolNumbers). The
// doubles are sobol_group's conversion (sobol_unit) in a plain loop, which the compiler
// vectorises with this file's instruction set (the baseline build has no unsigned-to-double
// conversion in lanes); the floats are sobol_unit_float's, in lanes, unit_float's of those
// doubles bit for bit. (A template on A, and A the conversions' tag, so that each instruction
// set's unit keeps its own copies: one inline function would be one definition for the linker
// to pick.)
template <class A>
void sobol_numbers(unsigned which, const SobolBatch& b, const SobolNumbers& to) {
  const std::size_t n = b.size();
  for (std::size_t c = 0; c < 4; ++c) {
    if (!(which & (1u << c))) continue;
    const uint32_t* u = b.u[c].data();
    if (double* d = to.as_double[c])
      for (std::size_t r = 0; r < n; ++r)
        d[r] = sobol_unit<A>(u[r]);
    if (float* f = to.as_float[c]) {
      constexpr std::size_t W = simd::kWidth<A>;
      std::size_t r = 0;
      for (; r + W <= n; r += W)
        simd::store<A>(f + r, sobol_unit_float(U32<A>::load_unaligned(u + r)));
      for (; r < n; ++r)  // the columns may end here: the rest row by row, the same steps
        f[r] = sobol_unit_float<A>(u[r]);
    }
  }
}

}  // namespace raylane::detail
