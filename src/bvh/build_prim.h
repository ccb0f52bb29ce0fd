// The builder's working data (src/bvh/build.cpp): one 32-byte record per primitive, boxes of
// four floats, and the bins of the binned SAH (Wald 2007, "On fast Construction of SAH-based
// Bounding Volume Hierarchies", §3). The loops over records and bins are in SIMD units of their
// own (bin_lanes_*.cpp, box_lanes.h), called through build_lanes.h; this header, and the code
// that calls them, has no xsimd.
#pragma once

#include <cstdint>
#include <limits>

#include "raylane/core/bounds3.h"
#include "raylane/core/prim_ref.h"

namespace raylane::bvh_build {

// SAH test costs as integers: multiples of kCostUnit. A kind's sah_test_cost, rounded to float,
// is a whole number of units (0.3f = 10066330 units, 1.0f = 2^25), so the summed cost of any
// set of prims is an exact integer and adds in one integer instruction, and the double it
// converts to (exactly, below 2^53 units) is the same number the float costs summed in double
// gave before (their sums were exact too, so neither the order nor the method changes a bit).
inline constexpr double kCostUnit = 1.0 / (1u << 25);
inline constexpr uint32_t cost_units(double sah_test_cost) {
  return uint32_t(double(float(sah_test_cost)) / kCostUnit + 0.5);
}

// 32 bytes, two to a cache line: {lo, ref} and {hi, cost} each load as four lanes, or the whole
// record as eight (the fourth and eighth are ignored). The centroid is not stored: lo + hi (twice
// the centroid, an affine image of it, which bins and splits the same way) is computed where it is
// needed, a non-finite sum read as 0 so that a huge primitive cannot make the centroid bounds
// infinite.
struct alignas(16) BuildPrim {
  float lo[3];
  PrimRef ref;
  float hi[3];
  uint32_t cost;  // SAH cost of testing it, in kCostUnit: its kind's sah_test_cost (never 0)
};
static_assert(sizeof(BuildPrim) == 32);

// A box as two rows of four floats (the fourth lane is unused); empty when lo > hi.
struct alignas(16) Box4 {
  float lo[4], hi[4];

  void clear() {
    for (int k = 0; k < 4; ++k)
      lo[k] = std::numeric_limits<float>::infinity(), hi[k] = -lo[k];
  }
  void extend(const Box4& b) {
    for (int k = 0; k < 3; ++k)
      lo[k] = b.lo[k] < lo[k] ? b.lo[k] : lo[k], hi[k] = b.hi[k] > hi[k] ? b.hi[k] : hi[k];
  }
  Bounds3f bounds() const {
    Bounds3f b;
    b.lo = {lo[0], lo[1], lo[2]};
    b.hi = {hi[0], hi[1], hi[2]};
    return b;
  }
};

// A node's primitives: their bounding box and the box of their (doubled) centroids.
struct NodeBounds {
  Box4 box, centroids;

  void clear() { box.clear(), centroids.clear(); }
  void extend(const NodeBounds& b) { box.extend(b.box), centroids.extend(b.centroids); }
};

inline constexpr int kMaxBins = 64;

// Maps a doubled centroid to its bin on each axis: bin = int((c − lo)·scale), clamped to
// [0, bins − 1] (a NaN goes to bin 0). scale is 0 on an axis where every centroid is equal.
struct BinGrid {
  float lo[4] = {0, 0, 0, 0};
  float scale[4] = {0, 0, 0, 0};
  int bins = 2;
};

// A bin's box as [lo, −hi] (lanes 3 and 7 unused, their contents undefined): with the high
// corner negated both corners grow by a min, so a record's box updates a bin in one min of eight
// lanes (or two of four) instead of a min and a max. Empty: every lane +inf. The min keeps the
// box exactly what a min of lo and a max of hi give, NaN and signed zeros alike (−x < −y exactly
// when y < x), so the bins, and the splits swept from them, are the same numbers.
struct alignas(32) BinBox {
  float lo[4], neg_hi[4];

  void clear() {
    for (int k = 0; k < 4; ++k)
      lo[k] = neg_hi[k] = std::numeric_limits<float>::infinity();
  }
  void extend(const BinBox& b) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = b.lo[k] < lo[k] ? b.lo[k] : lo[k];
      neg_hi[k] = b.neg_hi[k] < neg_hi[k] ? b.neg_hi[k] : neg_hi[k];
    }
  }
  Bounds3f bounds() const {
    Bounds3f b;
    b.lo = {lo[0], lo[1], lo[2]};
    b.hi = {-neg_hi[0], -neg_hi[1], -neg_hi[2]};
    return b;
  }
};

// The bins of all three axes: one pass over the primitives fills them (Wald 2007, §3.2). A
// bin's prims are not counted: every prim costs at least one unit, so a bin (or a side of a
// split) holds prims exactly when its summed cost is above 0.
struct BinSet {
  BinBox box[3][kMaxBins];
  uint64_t cost[3][kMaxBins];  // summed test cost in kCostUnit

  void clear(int bins) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < bins; ++b)
        box[a][b].clear(), cost[a][b] = 0;
  }
  void merge(const BinSet& o, int bins) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < bins; ++b)
        box[a][b].extend(o.box[a][b]), cost[a][b] += o.cost[a][b];
  }
};

}  // namespace raylane::bvh_build
