#include "bvh/sah_split.h"

#include <algorithm>
#include <cmath>

namespace raylane::bvh_build {

double half_area(const Bounds3f& b) {
  if (b.empty()) return 0;
  Vec3d d = Vec3d(b.hi) - Vec3d(b.lo);
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

namespace {

// A box grown bin by bin, its area in double (float extents up to FLT_MAX would overflow a
// float product). Hot: every node sweeps 2 × 3 × bins of them.
struct Sweep {
  float lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf};
  static constexpr float kInf = std::numeric_limits<float>::infinity();

  void add(const Box4& b) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], b.lo[k]);
      hi[k] = std::max(hi[k], b.hi[k]);
    }
  }
  double half_area() const {
    double dx = double(hi[0]) - lo[0], dy = double(hi[1]) - lo[1], dz = double(hi[2]) - lo[2];
    if (!(dx >= 0 && dy >= 0 && dz >= 0)) return 0;  // empty
    double a = dx * dy + dy * dz + dz * dx;
    return a <= std::numeric_limits<double>::max() ? a : std::numeric_limits<double>::max();
  }
};

}  // namespace

// Each axis is swept in three branch-free loops: boxes and costs from the right, from the left,
// then the choice. The bins' occupancy is data the branch predictor cannot learn (perf: the
// sweep was 28-36 % of the sphereflake's and the bunny's builds, with a mispredicted count test
// per bin), so an empty bin is added like any other — its box is empty (Box4::clear), so min
// and max leave the sweep's box as it was — and the candidates' costs go to an array that one
// last loop scans. Every value, and the first minimum chosen, are those of the loop with the
// tests (the test SahSplit.SweepEqualsTheDirectCosts holds it to a plain evaluation).
Split best_split(const BinSet& bins, const BinGrid& grid, const Bounds3f& box, uint32_t count,
                 double traversal_cost) {
  const int n = grid.bins;
  Split best;
  double parent_area = std::max(half_area(box), 1e-300);
  for (int axis = 0; axis < 3; ++axis) {
    if (!(grid.scale[axis] > 0)) continue;  // every centroid in one plane: no split here
    // Sweep from the right, then from the left, each accumulating box and cost (§3.2).
    double right_cost[kMaxBins], cost[kMaxBins];
    Sweep right;
    double tests = 0;
    for (int b = n - 1; b > 0; --b) {
      right.add(bins.box[axis][b]);
      tests += bins.cost[axis][b];
      right_cost[b - 1] = right.half_area() * tests;
    }
    Sweep left;
    tests = 0;
    for (int b = 0; b < n - 1; ++b) {
      left.add(bins.box[axis][b]);
      tests += bins.cost[axis][b];
      cost[b] = traversal_cost + (left.half_area() * tests + right_cost[b]) / parent_area;
    }
    uint32_t in_left = 0;
    for (int b = 0; b < n - 1; ++b) {
      in_left += bins.count[axis][b];
      if (in_left > 0 && in_left < count && cost[b] < best.cost) best = {axis, b, cost[b]};
    }
  }
  return best;
}

double binned_cost(const BinSet& bins, int bin_count) {
  double sum = 0;
  for (int b = 0; b < bin_count; ++b)
    sum += bins.cost[0][b];
  return sum;
}

}  // namespace raylane::bvh_build
