// Which blocks of a wavefront's path slots still hold a path with a ray in flight: the render
// loop finishes a tile whose block has none (src/render/wavefront/render_loop.cpp). In lanes,
// picked at run time as the other render kernels (src/render/render_lanes.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "raylane/simd/isa.h"

namespace raylane {

// Bit b set where some path[i] >> shift is b; every block below 64.
uint64_t blocks_of_paths(Isa isa, const uint32_t* path, std::size_t n, unsigned shift);

// The same, one path at a time: the lanes' reference.
inline uint64_t blocks_of_paths_ref(const uint32_t* path, std::size_t n, unsigned shift) {
  uint64_t bits = 0;
  for (std::size_t i = 0; i < n; ++i)
    bits |= uint64_t(1) << (path[i] >> shift);
  return bits;
}

}  // namespace raylane
