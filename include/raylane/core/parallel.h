// The one way raylane spreads work over threads (docs/design.md, "Threads"): the outermost
// loop owns them. Renderers run their tile loops in parallel; whole ray streams (raylane trace,
// the benchmarks) are split here into chunks; everything called from inside — the tracers,
// the kernels, the BVH's queries — runs on the calling thread and opens no parallel region.
#pragma once

#include <algorithm>
#include <cstddef>

namespace raylane {

// Calls f(begin, end) for consecutive chunks of [0, n) of `chunk` items (the last may be
// shorter), on OpenMP's threads, dynamically scheduled (for ray streams: kTraceChunk).
template <class F>
void parallel_chunks(std::size_t n, std::size_t chunk, F&& f) {
  const std::ptrdiff_t count = std::ptrdiff_t(n), step = std::ptrdiff_t(chunk);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t begin = 0; begin < count; begin += step)
    f(std::size_t(begin), std::size_t(std::min(count, begin + step)));
}

}  // namespace raylane
