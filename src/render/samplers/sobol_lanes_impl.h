// sobol_group (src/render/samplers/sobol.cpp) in lanes, one pixel per lane, instantiated per
// instruction set by src/render/render_lanes_<isa>.cpp. Include from nowhere else. The steps are
// sobol_group's own text (render/samplers/sobol_steps.h) on 32-bit unsigned lanes: the same
// values bit for bit (tests/render/sobol_test.cpp).
#pragma once

#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sobol.h"
#include "raylane/render/samplers/sobol_steps.h"
#include "raylane/simd/lane_numbers.h"
#include "raylane/simd/lane_u64.h"
#include "raylane/simd/lanes.h"

namespace raylane::detail {

template <class A>
using U32 = simd::UInts<A>;

// The rows' group seeds, group_seed_of (mix64 of the pixel's seed and the group's salt) split
// into the index's scramble (low half) and the components' seed (high half), in 64-bit lanes
// (simd::U64Lanes: AVX2 and SSE4.2 build the 64-bit product from 32-bit ones), written once
// with mix64 (render/samplers/rng.h).
template <class A>
void group_seeds(uint32_t group, SobolBatch& b) {
  using U64 = simd::U64Lanes<A>;
  constexpr std::size_t W = U64::V::size;
  const U64 salt(group_salt(group));
  // The columns' pointers in locals: the stores could alias the batch's own.
  const uint64_t* seed = b.seed.data();
  uint32_t *scramble = b.scramble.data(), *component = b.component.data();
  const std::size_t n = b.padded_size();
  for (std::size_t i = 0; i < n; i += W) {
    const U64 z = splitmix64_finaliser(U64(U64::V::load_unaligned(seed + i)) ^ salt);
    simd::store_halves<A>(scramble + i, component + i, z.v);
  }
}

// The groups' components in the set `which` (bit c: component c; 0 and 1 always): dimensions 2
// and 3 (the gathers) only if asked.
template <class A>
void sobol_groups_range(uint32_t reversed_index, uint32_t group, unsigned which, SobolBatch& b) {
  constexpr std::size_t W = simd::kWidth<A>;
  group_seeds<A>(group, b);
  // The columns' pointers in locals: the stores could alias the batch's own.
  const uint32_t *scramble = b.scramble.data(), *component = b.component.data();
  uint32_t* u[4] = {b.u[0].data(), b.u[1].data(), b.u[2].data(), b.u[3].data()};
  const std::size_t n = b.padded_size();
  for (std::size_t i = 0; i < n; i += W) {
    sobol_group_bits(U32<A>(reversed_index), U32<A>::load_unaligned(scramble + i),
                     U32<A>::load_unaligned(component + i), which,
                     [&](uint32_t c, const U32<A>& bits) { bits.store_unaligned(u[c] + i); });
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
