#include "raylane/render/film/tile_share.h"

#include <algorithm>
#include <functional>
#include <numeric>
#include <queue>
#include <utility>

namespace raylane {

std::vector<double> process_loads(const std::vector<double>& tile_cost, const TileShare& share) {
  std::vector<double> loads(share.count, 0.0);
  for (std::size_t t = 0; t < tile_cost.size(); ++t)
    loads[share.owner ? (*share.owner)[t] : t % share.count] += tile_cost[t];
  return loads;
}

double imbalance(const std::vector<double>& loads) {
  if (loads.empty()) return 1;
  double total = std::accumulate(loads.begin(), loads.end(), 0.0);
  if (!(total > 0)) return 1;
  return *std::max_element(loads.begin(), loads.end()) * double(loads.size()) / total;
}

std::vector<uint32_t> balance_tiles(const std::vector<double>& tile_cost, uint32_t processes) {
  std::vector<uint32_t> order(tile_cost.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return tile_cost[a] > tile_cost[b]; });
  // (load, process): the least loaded process on top, the lower number first among equals.
  using Slot = std::pair<double, uint32_t>;
  std::priority_queue<Slot, std::vector<Slot>, std::greater<Slot>> least;
  for (uint32_t p = 0; p < processes; ++p)
    least.push({0.0, p});
  std::vector<uint32_t> owner(tile_cost.size(), 0);
  for (uint32_t t : order) {
    auto [load, p] = least.top();
    least.pop();
    owner[t] = p;
    least.push({load + tile_cost[t], p});
  }
  return owner;
}

}  // namespace raylane
