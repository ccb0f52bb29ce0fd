#include "bvh/parallel_split.h"

#include <omp.h>

#include <algorithm>
#include <utility>
#include <vector>

namespace raylane::bvh_build {

namespace {

// Chunk t of [0, n) cut into `parts`: contiguous, sizes within one.
std::pair<uint32_t, uint32_t> chunk(uint32_t n, int t, int parts) {
  auto edge = [&](int k) { return uint32_t(uint64_t(n) * uint64_t(k) / uint64_t(parts)); };
  return {edge(t), edge(t + 1)};
}

// Ranges [first, last) of positions, read as one sequence.
class Ranges {
 public:
  void add(uint32_t first, uint32_t last) {
    if (first < last) ranges_.push_back({first, last}), size_ += last - first;
  }
  uint32_t size() const { return size_; }

  // Walks the sequence from its k-th element.
  class Cursor {
   public:
    Cursor(const Ranges& r, uint32_t k) : r_(r) {
      while (k >= r_.ranges_[range_].second - r_.ranges_[range_].first)
        k -= r_.ranges_[range_].second - r_.ranges_[range_].first, ++range_;
      pos_ = r_.ranges_[range_].first + k;
    }
    // The current position, then steps to the next.
    uint32_t next() {
      uint32_t p = pos_++;
      if (pos_ == r_.ranges_[range_].second && range_ + 1 < r_.ranges_.size())
        pos_ = r_.ranges_[++range_].first;
      return p;
    }

   private:
    const Ranges& r_;
    std::size_t range_ = 0;
    uint32_t pos_ = 0;
  };

 private:
  std::vector<std::pair<uint32_t, uint32_t>> ranges_;
  uint32_t size_ = 0;
};

}  // namespace

void bin_in_parallel(const BuildLanes& lanes, const BuildPrim* prims, uint32_t n,
                     const BinGrid& grid, int parts, BinSet& bins) {
  std::vector<BinSet> part(parts - 1);  // part 0 bins into `bins`
#pragma omp taskloop default(shared) num_tasks(parts)
  for (unsigned t = 0; t < unsigned(parts); ++t) {
    BinSet& mine = t == 0 ? bins : part[t - 1];
    mine.clear(grid.bins);
    auto [first, last] = chunk(n, t, parts);
    lanes.bin(prims + first, last - first, grid, mine);
  }
  for (int t = 1; t < parts; ++t)
    bins.merge(part[t - 1], grid.bins);
}

uint32_t partition_in_parallel(const BuildLanes& lanes, BuildPrim* prims, uint32_t n,
                               const BinGrid& grid, int axis, int last_left_bin, int parts,
                               NodeBounds& left, NodeBounds& right) {
  std::vector<uint32_t> lefts(parts, 0);
  std::vector<NodeBounds> lb(parts), rb(parts);
#pragma omp taskloop default(shared) num_tasks(parts)
  for (unsigned t = 0; t < unsigned(parts); ++t) {
    auto [b, e] = chunk(n, t, parts);
    lb[t].clear(), rb[t].clear();
    lefts[t] = lanes.partition(prims + b, e - b, grid, axis, last_left_bin, lb[t], rb[t]);
  }
  // Chunk t now holds [its lefts | its rights]. The final middle splits [0, n); right-side
  // prims before it and left-side prims after it are equally many and swap places.
  uint32_t mid = 0;
  for (int t = 0; t < parts; ++t)
    mid += lefts[t];
  Ranges misplaced_right, misplaced_left;
  left.clear(), right.clear();
  for (int t = 0; t < parts; ++t) {
    auto [b, e] = chunk(n, t, parts);
    uint32_t split = b + lefts[t];
    misplaced_right.add(split, std::min(e, mid));
    misplaced_left.add(std::max(b, mid), split);
    left.extend(lb[t]), right.extend(rb[t]);
  }
  const uint32_t k = misplaced_right.size();
  if (k == 0) return mid;
#pragma omp taskloop default(shared) num_tasks(parts)
  for (unsigned t = 0; t < unsigned(parts); ++t) {
    auto [k0, k1] = chunk(k, t, parts);
    if (k0 == k1) continue;
    Ranges::Cursor from(misplaced_right, k0), to(misplaced_left, k0);
    for (uint32_t i = k0; i < k1; ++i)
      std::swap(prims[from.next()], prims[to.next()]);
  }
  return mid;
}

NodeBounds bound_in_parallel(const BuildLanes& lanes, const BuildPrim* prims, uint32_t n,
                             int parts) {
  std::vector<NodeBounds> part(parts);
#pragma omp taskloop default(shared) num_tasks(parts)
  for (unsigned t = 0; t < unsigned(parts); ++t) {
    auto [b, e] = chunk(n, t, parts);
    part[t].clear();
    lanes.bound(prims + b, e - b, part[t]);
  }
  NodeBounds all;
  all.clear();
  for (int t = 0; t < parts; ++t)
    all.extend(part[t]);
  return all;
}

}  // namespace raylane::bvh_build
