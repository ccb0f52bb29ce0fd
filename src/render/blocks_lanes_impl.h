// blocks_of_paths (render_lanes.h) in lanes, instantiated per instruction set by
// src/render/render_lanes_<isa>.cpp. Include from nowhere else.
#pragma once

#include <cstddef>
#include <cstdint>

#include "raylane/simd/lanes.h"

namespace raylane::detail {

// The bit of each path's block (path >> shift, below 64) ORed into one word: in lanes, 1 shifted
// by the block into two 32-bit halves (simd::bit_of gives 0 for a shift of 32 or more, so each
// lane sets its bit in the one half it falls in); SSE4.2, without variable shifts, a path at a
// time.
template <class A>
uint64_t blocks_of_paths_range(const uint32_t* path, std::size_t n, unsigned shift) {
  using U = simd::UInts<A>;
  constexpr std::size_t W = std::size_t(simd::kWidth<A>);
  std::size_t i = 0;
  uint64_t bits = 0;
  if constexpr (W >= 8) {
    U lo(0u), hi(0u);
    const U half(32u);
    for (; i + W <= n; i += W) {
      const U block = U::load_unaligned(path + i) >> int(shift);
      lo = lo | simd::bit_of<A>(block), hi = hi | simd::bit_of<A>(block - half);
    }
    alignas(64) uint32_t low[W], high[W];
    lo.store_aligned(low), hi.store_aligned(high);
    for (std::size_t k = 0; k < W; ++k)
      bits |= uint64_t(low[k]) | uint64_t(high[k]) << 32;
  }
  for (; i < n; ++i)
    bits |= uint64_t(1) << (path[i] >> shift);
  return bits;
}

}  // namespace raylane::detail
