#include "bvh/sah_split.h"

#include "bvh/build_lanes.h"

#include <algorithm>
#include <cmath>

namespace raylane::bvh_build {

double half_area(const Bounds3f& b) {
  if (b.empty()) return 0;
  glm::dvec3 d = glm::dvec3(b.hi) - glm::dvec3(b.lo);
  double a = d.x * d.y + d.y * d.z + d.z * d.x;
  return std::isfinite(a) ? a : std::numeric_limits<double>::max();
}

BinGrid make_grid(const NodeBounds& bounds, int bins) {
  BinGrid g;
  g.bins = bins;
  for (int a = 0; a < 3; ++a) {
    double extent = double(bounds.centroids.hi[a]) - bounds.centroids.lo[a];
    // bins / extent can exceed the float range for a tiny extent: then every centroid but the
    // lowest lands in the last bin, which still splits them.
    double scale = extent > 0 ? bins / extent : 0.0;
    g.lo[a] = bounds.centroids.lo[a];
    g.scale[a] = float(std::min(scale, double(std::numeric_limits<float>::max())));
  }
  return g;
}

Split best_split(const BinSet& bins, const BinGrid& grid, const Bounds3f& box,
                 double traversal_cost, Isa isa) {
  return build_lanes(isa).sweep(bins, grid, std::max(half_area(box), 1e-300), traversal_cost);
}

const BuildLanes& build_lanes(Isa isa) {
  return for_isa(isa, kBuildLanesSse42, kBuildLanesAvx2, kBuildLanesAvx512);
}

double binned_cost(const BinSet& bins, int bin_count) {
  uint64_t sum = 0;
  for (int b = 0; b < bin_count; ++b)
    sum += bins.cost[0][b];
  return double(sum) * kCostUnit;
}

bool leaf_by_bound(const BuildPrim* prims, uint32_t n, const Bounds3f& box, double traversal_cost) {
  uint64_t leaf = 0;
  double spread = 0;
  for (uint32_t i = 0; i < n; ++i) {
    const BuildPrim& p = prims[i];
    Bounds3f b;
    b.lo = {p.lo[0], p.lo[1], p.lo[2]};
    b.hi = {p.hi[0], p.hi[1], p.hi[2]};
    double area = half_area(b);
    if (!(area < std::numeric_limits<double>::max())) return false;  // huge or NaN: bin it
    leaf += p.cost;
    spread += double(p.cost) * area;
  }
  double least_split = traversal_cost + spread * kCostUnit / std::max(half_area(box), 1e-300);
  return double(leaf) * kCostUnit <= least_split * (1 - 1e-9);
}

}  // namespace raylane::bvh_build
