// Which tiles of the image one process renders when several share it (`mpirun`,
// docs/cluster.md), and how the tiles are dealt again when their measured costs are uneven.
//
// A process renders its tiles for every pass, so each pixel's sum is formed in the same order
// as in a single process, and the processes' films have disjoint support. Tiles start dealt
// round-robin; `balance_tiles` deals them again by measured cost (the processes then swap the
// moved tiles' sums: docs/cluster.md, "Balance").
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

namespace raylane {

// Tile t covers kPathTile×kPathTile pixels, tiles numbered row-major over the image.
inline constexpr uint32_t kPathTile = 16;

// The tile of a film's pixel (x, row), rows top first as the film stores them. The render
// numbers its tiles row-major from the bottom row of pixels up (the camera's y counts up), so
// a film row counts from the other end.
inline uint64_t tile_of_film_pixel(uint32_t width, uint32_t height, uint32_t x, uint32_t row) {
  const uint64_t tiles_x = (width + kPathTile - 1) / kPathTile;
  return uint64_t((height - 1 - row) / kPathTile) * tiles_x + x / kPathTile;
}

struct TileShare {
  uint32_t index = 0, count = 1;
  // The process of each tile; without a table, tile t is process t mod count's.
  std::shared_ptr<const std::vector<uint32_t>> owner;
  bool owns(uint64_t tile) const { return owner ? (*owner)[tile] == index : tile % count == index; }
};

// Each process's summed cost under `share`'s ownership (share.count entries).
std::vector<double> process_loads(const std::vector<double>& tile_cost, const TileShare& share);

// The heaviest process's load over the mean load: 1 is perfect balance.
double imbalance(const std::vector<double>& loads);

// An owner for each tile that evens the processes' summed costs: the largest-processing-time-
// first rule (Graham 1969, "Bounds on multiprocessing timing anomalies"): tiles in decreasing
// cost, each to the least loaded process so far. The heaviest process then carries at most the
// mean plus one tile's cost. Ties go to the lower tile and process number, so the same costs
// always give the same table.
std::vector<uint32_t> balance_tiles(const std::vector<double>& tile_cost, uint32_t processes);

}  // namespace raylane
