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

std::vector<PrimRef> take_refs(const BuildPrim* prims, uint32_t n, int threads) {
  std::vector<PrimRef> refs(n);
#pragma omp parallel for num_threads(threads) if (n > 65536)
  for (int64_t i = 0; i < int64_t(n); ++i)
    refs[i] = prims[i].ref;
  return refs;
}

std::vector<std::vector<uint32_t>> permute_scene(Scene& scene, std::vector<PrimRef>& refs) {
  // A kind's k-th ref in leaf order gets row k: one pass sets the rows and the order (sized by
  // a first count, not grown: growing took 5.5 ms of the 1.31M mesh's build).
  std::vector<uint32_t> count(kPrimKindCount, 0);
  for (PrimRef r : refs)
    ++count[uint32_t(r.tag())];
  std::vector<std::vector<uint32_t>> order(kPrimKindCount);
  for (uint32_t k = 0; k < kPrimKindCount; ++k)
    order[k].reserve(count[k]);
  for (PrimRef& r : refs) {
    std::vector<uint32_t>& o = order[uint32_t(r.tag())];
    o.push_back(r.row());
    r = PrimRef(r.tag(), uint32_t(o.size() - 1));
  }
  scene.permute(order);
  return order;
}

std::vector<PrimRef> index_leaves(std::vector<BvhNode>& nodes, const std::vector<PrimRef>& refs,
                                  int threads) {
  // In chunks of nodes, the same for any number of threads: first the leaves of one kind are
  // pointed at their rows and the others' refs counted, then those refs are copied to where
  // the counts before them put them (sequential, the pass took 13 ms of the 1.31M mesh's
  // 2-thread build of 200).
  const int64_t n = int64_t(nodes.size());
  const int chunks = n > kParallelRows ? 64 : 1;
  auto chunk_begin = [&](int c) { return n * c / chunks; };
  std::vector<uint32_t> mixed_before(chunks + 1, 0);
#pragma omp parallel for num_threads(threads) if (chunks > 1)
  for (int c = 0; c < chunks; ++c) {
    uint32_t mixed = 0;
    for (int64_t i = chunk_begin(c); i < chunk_begin(c + 1); ++i) {
      BvhNode& leaf = nodes[i];
      if (!leaf.is_leaf()) continue;
      const PrimRef* r = refs.data() + leaf.index;
      const PrimTag tag = r[0].tag();
      if (std::all_of(r + 1, r + leaf.count, [tag](PrimRef x) { return x.tag() == tag; })) {
        leaf.index = r[0].bits();
        leaf.flags = BvhNode::kOneKind;
      } else {
        mixed += leaf.count;
      }
    }
    mixed_before[c + 1] = mixed;
  }
  for (int c = 0; c < chunks; ++c)
    mixed_before[c + 1] += mixed_before[c];
  std::vector<PrimRef> mixed(mixed_before[chunks]);
#pragma omp parallel for num_threads(threads) if (chunks > 1 && !mixed.empty())
  for (int c = 0; c < chunks; ++c) {
    uint32_t at = mixed_before[c];
    for (int64_t i = chunk_begin(c); i < chunk_begin(c + 1); ++i) {
      BvhNode& leaf = nodes[i];
      if (!leaf.is_leaf() || leaf.is_one_kind()) continue;
      std::copy(refs.begin() + leaf.index, refs.begin() + leaf.index + leaf.count,
                mixed.begin() + at);
      leaf.index = at;
      at += leaf.count;
    }
  }
  return mixed;
}

}  // namespace raylane::bvh_build
