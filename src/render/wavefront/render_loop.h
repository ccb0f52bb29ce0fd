// A thread's share of a pass: it claims tiles from one counter shared by the threads (as a
// dynamic schedule would hand them out), and steps its wavefront until every path has ended.
// With the Sobol sampler a wavefront refills: whenever its rays fall below kRefillBelow, the
// next tile's camera rays join the paths still going, so the tracer and the lanes keep getting
// full batches instead of the few long paths a lone tile ends with (Laine, Karras and Aila 2013,
// "Megakernels Considered Harmful", regenerate paths in the same way). Every number a path
// draws depends on its pixel, pass and depth alone, and each pixel gets one sample per pass, so
// the image is the same bit for bit whatever shares a wavefront. MT19937 draws in the order
// of one tile's rows: its wavefront takes a tile only when empty. Include from src/render only.
#pragma once

#include <atomic>
#include <cstddef>
#include <vector>

#include "raylane/render/film/region.h"
#include "raylane/render/film/tile_share.h"
#include "render/wavefront/stages.h"

namespace raylane::path_detail {

// A wavefront takes the next tile while it holds fewer rays than this (a tile brings kTile²).
inline constexpr std::size_t kRefillBelow = 192;

// The tiles of one pass that this process renders (its MPI share, inside the region if any),
// handed out one at a time to whichever thread asks.
class TileClaims {
 public:
  TileClaims(const Camera& cam, const TileShare& share, const PathSettings& settings);
  // The next tile for the caller, or false when none is left.
  bool next(std::ptrdiff_t& tile);
  uint32_t tiles_x() const { return tiles_x_; }

 private:
  std::atomic<std::ptrdiff_t> next_{0};
  std::ptrdiff_t tiles_;
  uint32_t tiles_x_, width_, height_;
  const TileShare& share_;
  const PathSettings& settings_;
};

// The calling thread's tiles of the pass, claimed from `claims` and rendered into `film`; where
// `tile_seconds` is not empty, each finished tile's share of the thread's CPU time goes into it.
void render_claimed_tiles(ThreadContext& ctx, const Camera& cam, TileClaims& claims, Film& film,
                          std::vector<double>& tile_seconds);

}  // namespace raylane::path_detail
