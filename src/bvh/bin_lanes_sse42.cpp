// The builder's loops over its primitive records, in four SSE4.2 lanes: a record's box is one
// row of lanes, so a bin's box grows by one min and one max instead of six scalar ones (GCC
// does not vectorise the scalar loop). SSE4.2 is every x86-64 raylane runs on, and four lanes
// hold a box exactly, so wider instruction sets would gain nothing here. The SAH sweep over the
// bins (sweep_lanes.h) is compiled here for SSE4.2 too, and for AVX2 and AVX-512 in their units.
#include "bvh/build_lanes.h"
#include "bvh/build_prim.h"
#include "bvh/sweep_lanes.h"
#include "raylane/simd/lanes.h"

static_assert(XSIMD_WITH_SSE4_2, "this file must be compiled with SSE4.2");

namespace raylane::bvh_build {

namespace {

using A = xsimd::sse4_2;
using F = simd::Floats<A>;
using I = simd::Ints<A>;

F load_lo(const BuildPrim& p) {
  return F::load_aligned(p.lo);
}
F load_hi(const BuildPrim& p) {
  return F::load_aligned(p.hi);
}

// lo + hi, with a non-finite lane read as 0 (see BuildPrim).
F doubled_centroid(const F& lo, const F& hi) {
  F c = lo + hi;
  return simd::select(xsimd::abs(c) < F(std::numeric_limits<float>::infinity()), c, F(0.0f));
}

// The bin of each lane of c: (c − lo)·scale clamped to [0, top] in float before the
// conversion (max_keep maps NaN to 0, min_keep keeps the clamp: simd/lanes.h).
I bin_index(const F& c, const F& lo, const F& scale, const F& top) {
  F x = (c - lo) * scale;
  x = simd::min_keep<A>(simd::max_keep<A>(x, F(0.0f)), top);
  return xsimd::batch_cast<int32_t>(x);
}

// Running bounds of boxes and centroids, in registers.
struct LaneBounds {
  F lo, hi, clo, chi;

  explicit LaneBounds(const NodeBounds& b)
      : lo(F::load_aligned(b.box.lo)),
        hi(F::load_aligned(b.box.hi)),
        clo(F::load_aligned(b.centroids.lo)),
        chi(F::load_aligned(b.centroids.hi)) {}
  void add(const F& plo, const F& phi, const F& c) {
    lo = simd::min_keep<A>(plo, lo), hi = simd::max_keep<A>(phi, hi);
    clo = simd::min_keep<A>(c, clo), chi = simd::max_keep<A>(c, chi);
  }
  void store(NodeBounds& b) const {
    lo.store_aligned(b.box.lo), hi.store_aligned(b.box.hi);
    clo.store_aligned(b.centroids.lo), chi.store_aligned(b.centroids.hi);
  }
};

}  // namespace

void bound_prims(const BuildPrim* prims, uint32_t n, NodeBounds& bounds) {
  LaneBounds acc(bounds);
  for (uint32_t i = 0; i < n; ++i) {
    F lo = load_lo(prims[i]), hi = load_hi(prims[i]);
    acc.add(lo, hi, doubled_centroid(lo, hi));
  }
  acc.store(bounds);
}

namespace {

// Adds one record to the bins of all three axes (inlined: a call per record cost a tenth of the
// binning in the profile, its constants reloaded each time).
[[gnu::always_inline]] inline void bin_one(const BuildPrim& p, const F& glo, const F& scale,
                                           const F& top, BinSet& bins) {
  alignas(16) int32_t idx[4];
  F lo = load_lo(p), hi = load_hi(p);
  bin_index(doubled_centroid(lo, hi), glo, scale, top).store_aligned(idx);
  for (int a = 0; a < 3; ++a) {
    Box4& b = bins.box[a][idx[a]];
    simd::min_keep<A>(lo, F::load_aligned(b.lo)).store_aligned(b.lo);
    simd::max_keep<A>(hi, F::load_aligned(b.hi)).store_aligned(b.hi);
    bins.cost[a][idx[a]] += p.cost;
  }
}

// Below this many records one set of bins is used; above it, two.
constexpr uint32_t kTwoSetsFrom = 256;

}  // namespace

// Neighbouring records usually fall in the same bins, and each update of a bin waits for the
// previous one's store; above kTwoSetsFrom records, even and odd records go to two sets of
// bins, merged at the end, so two chains of updates overlap.
void bin_prims(const BuildPrim* prims, uint32_t n, const BinGrid& grid, BinSet& bins) {
  const F glo = F::load_unaligned(grid.lo), scale = F::load_unaligned(grid.scale);
  const F top(float(grid.bins - 1));
  if (n < kTwoSetsFrom) {
    for (uint32_t i = 0; i < n; ++i)
      bin_one(prims[i], glo, scale, top, bins);
    return;
  }
  BinSet odd;
  odd.clear(grid.bins);
  uint32_t i = 0;
  for (; i + 1 < n; i += 2) {
    bin_one(prims[i], glo, scale, top, bins);
    bin_one(prims[i + 1], glo, scale, top, odd);
  }
  if (i < n) bin_one(prims[i], glo, scale, top, bins);
  bins.merge(odd, grid.bins);
}

uint32_t partition_prims(BuildPrim* prims, uint32_t n, const BinGrid& grid, int axis,
                         int last_left_bin, NodeBounds& left, NodeBounds& right) {
  const F glo = F::load_unaligned(grid.lo), scale = F::load_unaligned(grid.scale);
  const F top(float(grid.bins - 1));
  LaneBounds l(left), r(right);
  alignas(16) int32_t idx[4];
  // Classifies prims[i] and adds it to the bounds of its side.
  auto goes_left = [&](uint32_t i) {
    F lo = load_lo(prims[i]), hi = load_hi(prims[i]);
    F c = doubled_centroid(lo, hi);
    bin_index(c, glo, scale, top).store_aligned(idx);
    bool is_left = idx[axis] <= last_left_bin;
    (is_left ? l : r).add(lo, hi, c);
    return is_left;
  };
  // Hoare's scheme: each record is classified once; misplaced pairs are swapped.
  uint32_t i = 0, j = n;
  while (true) {
    while (i < j && goes_left(i))
      ++i;
    while (i < j && !goes_left(j - 1))
      --j;
    if (i >= j) break;
    std::swap(prims[i], prims[j - 1]);
    ++i, --j;
  }
  l.store(left), r.store(right);
  return i;
}

const BuildLanes kBuildLanesSse42 = {lanes::sweep_bins<A>};

}  // namespace raylane::bvh_build
