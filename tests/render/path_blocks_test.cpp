// The blocks' bits in lanes (render/path_blocks.h) against the path-by-path reference, at every
// instruction set this CPU has: every length from 0 to past two registers (each lane of a last
// partial batch), blocks on both sides of bit 32 and at 0 and 63, and a block that only the last
// path names.
#include "raylane/render/path_blocks.h"

#include <gtest/gtest.h>

#include <vector>

#include "raylane/core/strings.h"
#include "raylane/render/samplers/rng.h"

namespace raylane {
namespace {

TEST(PathBlocks, LanesSetTheReferencesBits) {
  Rng rng(5);
  constexpr unsigned kShift = 8;
  for (Isa isa : supported_isas())
    for (std::size_t n = 0; n <= 40; ++n)
      for (int blocks : {1, 5, 31, 33, 64}) {
        SCOPED_TRACE(cat(isa_name(isa), " paths ", n, " blocks ", blocks));
        std::vector<uint32_t> path(n);
        for (uint32_t& p : path)
          p = uint32_t(rng.uniform() * blocks * 256);
        EXPECT_EQ(blocks_of_paths(isa, path.data(), n, kShift),
                  blocks_of_paths_ref(path.data(), n, kShift));
        if (n == 0) continue;
        path.back() = 63 * 256 + 255;  // the last block, named last
        EXPECT_EQ(blocks_of_paths(isa, path.data(), n, kShift) >> 63, 1u);
        path.back() = 0;
        EXPECT_EQ(blocks_of_paths(isa, path.data(), n, kShift) & 1u, 1u);
      }
}

}  // namespace
}  // namespace raylane
