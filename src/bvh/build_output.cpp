#include "bvh/build_output.h"

#include <omp.h>

#include <algorithm>

#include "bvh/sah_split.h"
#include "raylane/scene/scene.h"

namespace raylane::bvh_build {

namespace {

// Below this many rows a table is read by the calling thread: a parallel region costs
// microseconds, the whole of a small scene's gather.
constexpr int64_t kParallelRows = 4096;

template <class Kind, class Table>
void gather_rows(const Table& table, int64_t first, int64_t last, BuildPrim* out) {
  constexpr uint32_t cost = cost_units(Kind::sah_test_cost);
  static_assert(cost > 0, "a prim of no cost would make a bin look empty (BinSet)");
  for (int64_t row = first; row < last; ++row) {
    Bounds3f b = table.bounds(uint32_t(row));
    out[row] = {{b.lo.x, b.lo.y, b.lo.z},
                PrimRef(tag_of<Kind>, uint32_t(row)),
                {b.hi.x, b.hi.y, b.hi.z},
                cost};
  }
}

}  // namespace

MallocPtr<BuildPrim> gather(const Scene& scene, int threads) {
  MallocPtr<BuildPrim> prims = allocate_unwritten<BuildPrim>(scene.primitive_count());
  std::size_t offset = 0;
  PrimKinds::for_each([&](auto kind) {
    using Kind = decltype(kind);
    const auto& table = scene.table<Kind>();
    const int64_t rows = table.size();
    BuildPrim* out = prims.get() + offset;
    if (threads < 2 || rows <= kParallelRows) {
      gather_rows<Kind>(table, 0, rows, out);
    } else {
#pragma omp parallel num_threads(threads)
      {
        // Contiguous blocks, so each thread first touches the pages it writes.
        const int64_t t = omp_get_thread_num(), n = omp_get_num_threads();
        gather_rows<Kind>(table, rows * t / n, rows * (t + 1) / n, out);
      }
    }
    offset += rows;
  });
  return prims;
}

void copy_tree(const BvhNode* slots, uint32_t inner, const BuildPrim* prims, double traversal_cost,
               std::vector<BvhNode>& out, BvhStats& s) {
  out.clear();
  out.reserve(2 * std::size_t(inner) + 1);
  const double root_area = std::max(half_area(slots[0].bounds()), 1e-300);
  // Counts a node as copied (in out's order, so the SAH cost is summed the same every time).
  auto tally = [&](const BvhNode& n, uint32_t depth) {
    double rel = half_area(n.bounds()) / root_area;
    if (!n.is_leaf()) {
      ++s.inner_nodes;
      s.sah_cost += rel * traversal_cost;
      return;
    }
    ++s.leaves;
    s.depth = std::max(s.depth, depth);
    for (uint32_t i = n.index; i < n.index + n.count; ++i)
      s.sah_cost += rel * kind_sah_test_cost(prims[i].ref.tag());
    if (s.leaf_size_histogram.size() <= n.count) s.leaf_size_histogram.resize(n.count + 1);
    ++s.leaf_size_histogram[n.count];
  };
  struct Todo {
    uint32_t slot, at, depth;  // an inner node's slot, its place in `out`, its depth
  };
  std::vector<Todo> stack;
  out.push_back(slots[0]);
  tally(slots[0], 0);
  if (!slots[0].is_leaf()) stack.push_back({0, 0, 0});
  while (!stack.empty()) {
    Todo t = stack.back();
    stack.pop_back();
    const uint32_t child = slots[t.slot].index, at = uint32_t(out.size());
    // Each pair's place is read from its parent: a chain of cache misses through slots the
    // build wrote long before (41 ms of the 1.31M mesh's build; 27 with these prefetches, which
    // 32 or 64 slots ahead do not beat). The left child's pairs follow this one in the slots
    // (Pending::desc); the right child's place is known once the right child is read.
    __builtin_prefetch(slots + child + 16);
    out[t.at].index = at;
    for (uint32_t k : {child, child + 1}) {
      out.push_back(slots[k]);
      tally(slots[k], t.depth + 1);
    }
    if (!slots[child + 1].is_leaf()) __builtin_prefetch(slots + slots[child + 1].index);
    for (uint32_t k : {1u, 0u})  // the left child's pairs first
      if (!slots[child + k].is_leaf()) stack.push_back({child + k, at + k, t.depth + 1});
  }
}

std::vector<PrimRef> take_refs(const BuildPrim* prims, uint32_t n, int threads) {
  std::vector<PrimRef> refs(n);
#pragma omp parallel for num_threads(threads) if (n > 65536)
  for (int64_t i = 0; i < int64_t(n); ++i)
    refs[i] = prims[i].ref;
  return refs;
}

std::vector<std::vector<uint32_t>> permute_scene(Scene& scene, std::vector<PrimRef>& refs) {
  std::vector<std::vector<uint32_t>> order(kPrimKindCount);
  for (PrimRef r : refs)
    order[uint32_t(r.tag())].push_back(r.row());
  std::vector<std::vector<uint32_t>> new_row = scene.permute(order);
  for (PrimRef& r : refs)
    r = PrimRef(r.tag(), new_row[uint32_t(r.tag())][r.row()]);
  return order;
}

}  // namespace raylane::bvh_build
