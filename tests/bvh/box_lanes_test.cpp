// The builder's loops over its records (src/bvh/box_lanes.h, through build_lanes.h) at every
// instruction set the CPU has, against a plain scalar statement of what they compute: a
// record's doubled centroid lo + hi (0 where not finite), its bin (c − lo)·scale clamped to
// [0, bins − 1] and truncated, each bin's box the min of its prims' low corners and the max of
// their high corners (a NaN coordinate never replacing a bound), and a partition that puts
// exactly the prims whose bin is at most the split's on the left. Boxes must be equal to the
// bit; records include NaN, infinite, huge and signed-zero coordinates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "bvh/build_lanes.h"

namespace raylane::bvh_build {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// x < acc ? x : acc and x > acc ? x : acc: simd::min_keep and max_keep's contract.
float min_keep(float x, float acc) {
  return x < acc ? x : acc;
}
float max_keep(float x, float acc) {
  return x > acc ? x : acc;
}

float centroid(const BuildPrim& p, int k) {
  float c = p.lo[k] + p.hi[k];
  return std::fabs(c) < kInf ? c : 0.0f;
}

int bin_of(const BuildPrim& p, const BinGrid& g, int axis) {
  float x = (centroid(p, axis) - g.lo[axis]) * g.scale[axis];
  return int(min_keep(max_keep(x, 0.0f), float(g.bins - 1)));
}

void add(Box4& b, const BuildPrim& p) {
  for (int k = 0; k < 3; ++k)
    b.lo[k] = min_keep(p.lo[k], b.lo[k]), b.hi[k] = max_keep(p.hi[k], b.hi[k]);
}

NodeBounds bounds_of(const std::vector<BuildPrim>& prims) {
  NodeBounds nb;
  nb.clear();
  for (const BuildPrim& p : prims) {
    add(nb.box, p);
    for (int k = 0; k < 3; ++k) {
      float c = centroid(p, k);
      nb.centroids.lo[k] = min_keep(c, nb.centroids.lo[k]);
      nb.centroids.hi[k] = max_keep(c, nb.centroids.hi[k]);
    }
  }
  return nb;
}

bool same_bits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Boxes equal to the bit; the centroids' high corner up to the sign of a zero (box_lanes.h:
// make_grid cannot see it).
void expect_bounds(const NodeBounds& got, const NodeBounds& want, const char* what) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(same_bits(got.box.lo[k], want.box.lo[k])) << what << " lo " << k;
    EXPECT_TRUE(same_bits(got.box.hi[k], want.box.hi[k])) << what << " hi " << k;
    EXPECT_TRUE(same_bits(got.centroids.lo[k], want.centroids.lo[k])) << what << " clo " << k;
    EXPECT_EQ(got.centroids.hi[k], want.centroids.hi[k]) << what << " chi " << k;
  }
}

// Random records: mostly ordinary boxes, some with a NaN, an infinite or a huge coordinate, or
// with lo = −hi (a centroid of zero, of either sign); costs of 0.3 and 1.
std::vector<BuildPrim> random_prims(std::mt19937& rng, uint32_t n) {
  std::uniform_real_distribution<float> u(-5.0f, 5.0f), ext(0.0f, 2.0f), pick(0.0f, 1.0f);
  std::vector<BuildPrim> prims(n);
  for (uint32_t i = 0; i < n; ++i) {
    BuildPrim& p = prims[i];
    for (int k = 0; k < 3; ++k) {
      p.lo[k] = u(rng);
      p.hi[k] = p.lo[k] + ext(rng);
      float odd = pick(rng);
      if (odd < 0.02f) p.lo[k] = std::numeric_limits<float>::quiet_NaN();
      if (odd > 0.98f) p.hi[k] = kInf;
      if (odd > 0.96f && odd <= 0.98f) p.hi[k] = 3e38f, p.lo[k] = 2e38f;  // c overflows
      if (odd > 0.90f && odd <= 0.93f) p.lo[k] = -p.hi[k];
      if (odd > 0.93f && odd <= 0.96f) p.lo[k] = -0.0f, p.hi[k] = 0.0f;
    }
    p.ref = PrimRef(PrimTag(0), i);
    p.cost = cost_units(i % 3 ? 0.3 : 1.0);
  }
  return prims;
}

BinGrid grid_for(const std::vector<BuildPrim>& prims, int bins) {
  return make_grid(bounds_of(prims), bins);
}

TEST(BoxLanes, EveryIsaBinsAsTheScalarDefinition) {
  std::mt19937 rng(23);
  for (int trial = 0; trial < 300; ++trial) {
    const uint32_t n = 1 + uint32_t(trial * 7 % 700);  // both sides of the two-set threshold
    std::vector<BuildPrim> prims = random_prims(rng, n);
    const BinGrid grid = grid_for(prims, 2 + trial % 31);
    BinSet want;
    want.clear(grid.bins);
    for (const BuildPrim& p : prims)
      for (int a = 0; a < 3; ++a) {
        int b = bin_of(p, grid, a);
        Bounds3f box = want.box[a][b].bounds();
        Box4 grown;
        for (int k = 0; k < 3; ++k)
          grown.lo[k] = box.lo[k], grown.hi[k] = box.hi[k];
        add(grown, p);
        for (int k = 0; k < 3; ++k)
          want.box[a][b].lo[k] = grown.lo[k], want.box[a][b].neg_hi[k] = -grown.hi[k];
        want.cost[a][b] += p.cost;
      }
    for (Isa isa : supported_isas()) {
      BinSet got;
      got.clear(grid.bins);
      build_lanes(isa).bin(prims.data(), n, grid, got);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < grid.bins; ++b) {
          ASSERT_EQ(got.cost[a][b], want.cost[a][b]) << trial << ' ' << isa_name(isa);
          for (int k = 0; k < 3; ++k) {
            ASSERT_TRUE(same_bits(got.box[a][b].lo[k], want.box[a][b].lo[k]))
                << trial << ' ' << isa_name(isa) << ' ' << a << ' ' << b << ' ' << k;
            ASSERT_TRUE(same_bits(got.box[a][b].neg_hi[k], want.box[a][b].neg_hi[k]))
                << trial << ' ' << isa_name(isa) << ' ' << a << ' ' << b << ' ' << k;
          }
        }
    }
  }
}

TEST(BoxLanes, EveryIsaBoundsAndPartitionsAsTheScalarDefinition) {
  std::mt19937 rng(29);
  for (int trial = 0; trial < 300; ++trial) {
    const uint32_t n = 1 + uint32_t(trial * 13 % 500);
    const std::vector<BuildPrim> prims = random_prims(rng, n);
    const BinGrid grid = grid_for(prims, 2 + trial % 15);
    const int axis = trial % 3, last_left = trial % (grid.bins - 1);
    std::vector<BuildPrim> want_left, want_right;
    for (const BuildPrim& p : prims)
      (bin_of(p, grid, axis) <= last_left ? want_left : want_right).push_back(p);
    for (Isa isa : supported_isas()) {
      const BuildLanes& lanes = build_lanes(isa);
      NodeBounds all;
      all.clear();
      lanes.bound(prims.data(), n, all);
      expect_bounds(all, bounds_of(prims), isa_name(isa).data());

      std::vector<BuildPrim> moved = prims;
      NodeBounds left, right;
      left.clear(), right.clear();
      uint32_t mid = lanes.partition(moved.data(), n, grid, axis, last_left, left, right);
      ASSERT_EQ(mid, want_left.size()) << trial << ' ' << isa_name(isa);
      std::vector<PrimRef> got_left, wanted;
      for (uint32_t i = 0; i < mid; ++i)
        got_left.push_back(moved[i].ref);
      for (const BuildPrim& p : want_left)
        wanted.push_back(p.ref);
      std::sort(got_left.begin(), got_left.end());
      std::sort(wanted.begin(), wanted.end());
      ASSERT_EQ(got_left, wanted) << trial << ' ' << isa_name(isa);
      expect_bounds(left, bounds_of(want_left), "left");
      expect_bounds(right, bounds_of(want_right), "right");
    }
  }
}

}  // namespace
}  // namespace raylane::bvh_build
