// The builder's slots compacted into the node array (build_output.h, compact_tree). A node's
// slot is fixed by its prims' range and the slots are in depth-first pair order, so the array is
// the used slots in slot order, each child index replaced by its slot's rank among the used
// ones. With the ranks from one bit per slot and a count per 64 slots, any subtree knows where
// its nodes go, so subtrees are copied by tasks: the copy before was one thread chasing child
// indices through the slots (23 ms of the 1.31M mesh's build). Copying the used slots in slot
// order instead, streaming, took longer (31 ms at 1 thread): it reads the unused slots too.
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cstring>

#include "bvh/build_output.h"
#include "bvh/sah_split.h"
#include "raylane/prims/prim_list.h"

namespace raylane::bvh_build {

namespace {

// Used slots as bits, and the number of used slots before each word.
struct SlotRanks {
  std::vector<uint64_t> bits;
  std::vector<uint32_t> before;  // before[w]: used slots in words [0, w)

  uint32_t operator()(uint32_t slot) const {
    const uint64_t below = bits[slot >> 6] & ((uint64_t(1) << (slot & 63)) - 1);
    return before[slot >> 6] + uint32_t(std::popcount(below));
  }
};

// 64 flags (bytes of 0 or 1) from `used`, as bits: eight at a time by one multiplication, which
// moves byte i's low bit to bit 56 + i without carries (each product bit comes from one byte).
uint64_t pack_flags(const uint8_t* used, uint32_t first, uint32_t count) {
  uint64_t word = 0;
  uint32_t k = 0;
  for (; k + 8 <= count; k += 8) {
    uint64_t bytes;
    std::memcpy(&bytes, used + first + k, 8);
    word |= ((bytes * 0x0102040810204080ull) >> 56) << k;
  }
  for (; k < count; ++k)
    word |= uint64_t(used[first + k] != 0) << k;
  return word;
}

// The statistics of some nodes, summed in the order they are copied.
struct Tally {
  uint32_t inner = 0, leaves = 0, depth = 0;
  double sah = 0;
  std::vector<uint32_t> histogram;

  void add(const BvhNode& n, uint32_t depth_of_n, double root_area, const BuildPrim* prims,
           double traversal_cost) {
    const double rel = half_area(n.bounds()) / root_area;
    if (!n.is_leaf()) {
      ++inner;
      sah += rel * traversal_cost;
      return;
    }
    ++leaves;
    depth = std::max(depth, depth_of_n);
    for (uint32_t i = n.index; i < n.index + n.count; ++i)
      sah += rel * kind_sah_test_cost(prims[i].ref.tag());
    if (histogram.size() <= n.count) histogram.resize(n.count + 1);
    ++histogram[n.count];
  }
  void add(const Tally& t) {
    inner += t.inner, leaves += t.leaves, depth = std::max(depth, t.depth), sah += t.sah;
    if (histogram.size() < t.histogram.size()) histogram.resize(t.histogram.size());
    for (std::size_t k = 0; k < t.histogram.size(); ++k)
      histogram[k] += t.histogram[k];
  }
};

// Inner nodes at this depth have their subtrees copied by tasks of their own: at most 2^6,
// the same ones for any number of threads, so the statistics are summed in the same order.
constexpr uint32_t kTaskDepth = 6;
constexpr uint32_t kParallelSlots = 1u << 16;

class Copier {
 public:
  Copier(const BvhNode* slots, const SlotRanks& rank, const BuildPrim* prims, double traversal_cost,
         BvhNode* out)
      : slots_(slots),
        rank_(rank),
        prims_(prims),
        traversal_(traversal_cost),
        root_area_(std::max(half_area(slots[0].bounds()), 1e-300)),
        out_(out) {}

  // Copies the root, then the nodes above kTaskDepth (and their children), depth first;
  // returns the inner nodes at kTaskDepth, whose children are not copied yet.
  std::vector<uint32_t> copy_top(Tally& t) const {
    place(0, t);
    std::vector<uint32_t> deeper;
    if (!slots_[0].is_leaf()) copy_below(0, t, kTaskDepth, &deeper);
    return deeper;
  }
  // Copies the descendants of the inner node in `slot`. Each node's place is its slot's rank,
  // so the order of the visit sets only the order the statistics are summed in, and what is
  // worth prefetching: depth first, the left subtree's pairs first, which is slot order.
  void copy_below(uint32_t slot, Tally& t, uint32_t stop_depth = ~0u,
                  std::vector<uint32_t>* deeper = nullptr) const {
    std::vector<uint32_t> stack = {slot};
    while (!stack.empty()) {
      const uint32_t s = stack.back();
      stack.pop_back();
      if (slots_[s].flags >= stop_depth) {
        deeper->push_back(s);
        continue;
      }
      // The children's pair was written long before: a chain of cache misses without these
      // prefetches (the left child's pairs follow this one in the slots; the right child's
      // place is known once the right child is read).
      const uint32_t child = slots_[s].index;
      __builtin_prefetch(slots_ + child + 16);
      place(child, t), place(child + 1, t);
      if (!slots_[child + 1].is_leaf()) __builtin_prefetch(slots_ + slots_[child + 1].index);
      for (uint32_t k : {child + 1, child})  // the left child's popped first
        if (!slots_[k].is_leaf()) stack.push_back(k);
    }
  }

 private:
  // Writes the node of `slot` to its place, its child index renumbered and its flags byte (its
  // depth, set by the builder) zeroed.
  void place(uint32_t slot, Tally& t) const {
    BvhNode n = slots_[slot];
    const uint32_t depth = n.flags;
    n.flags = 0;
    if (!n.is_leaf()) n.index = rank_(n.index);
    t.add(n, depth, root_area_, prims_, traversal_);
    out_[rank_(slot)] = n;
  }

  const BvhNode* slots_;
  const SlotRanks& rank_;
  const BuildPrim* prims_;
  const double traversal_, root_area_;
  BvhNode* out_;
};

}  // namespace

void compact_tree(const BvhNode* slots, const uint8_t* used, uint32_t slot_count,
                  const BuildPrim* prims, double traversal_cost, int threads,
                  std::vector<BvhNode>& out, BvhStats& s) {
  const uint32_t words = (slot_count + 63) / 64;
  SlotRanks rank;
  rank.bits.resize(words), rank.before.resize(words + 1);
  rank.before[0] = 0;
  for (uint32_t w = 0; w < words; ++w) {
    rank.bits[w] = pack_flags(used, 64 * w, std::min(64u, slot_count - 64 * w));
    rank.before[w + 1] = rank.before[w] + uint32_t(std::popcount(rank.bits[w]));
  }
  out.resize(rank.before[words]);  // not written (BvhNode's constructor)

  Copier copier(slots, rank, prims, traversal_cost, out.data());
  Tally top;
  const std::vector<uint32_t> subtrees = copier.copy_top(top);
  std::vector<Tally> part(subtrees.size());
  // A parallel region costs microseconds: not worth it for a small tree (the bunny's 7k slots).
  const bool parallel = threads > 1 && part.size() > 1 && slot_count >= kParallelSlots;
#pragma omp parallel for num_threads(threads) schedule(dynamic) if (parallel)
  for (int64_t k = 0; k < int64_t(subtrees.size()); ++k)
    copier.copy_below(subtrees[k], part[k]);
  for (const Tally& t : part)
    top.add(t);
  s.inner_nodes += top.inner, s.leaves += top.leaves, s.depth = std::max(s.depth, top.depth);
  s.sah_cost += top.sah;
  s.leaf_size_histogram = std::move(top.histogram);
}

}  // namespace raylane::bvh_build
