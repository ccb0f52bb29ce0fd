// Helpers shared by the SoA tables. Every table exposes `auto columns()` (a std::tie of its
// column vectors); these work on any table through it. A table may also have optional columns
// (`auto optional_columns()`), empty unless a scene needs them (mesh UVs): they are permuted
// and counted when they hold rows, and never reserved ahead.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <tuple>
#include <type_traits>
#include <vector>

namespace raylane {

template <class T>
std::size_t column_bytes(const std::vector<T>& c) {
  return c.size() * sizeof(T);
}

// Reorders a column so that new row i is old row order[i], written into `spare`, which then
// holds the column's old rows. A spare of the column's size is written without being zeroed
// or faulted in first (a new vector was both: 19 columns of 5 MB for the 1.31M mesh).
template <class T>
void permute_column(std::vector<T>& c, std::span<const uint32_t> order, std::vector<T>& spare) {
  if (spare.size() != order.size()) {
    spare.clear();
    spare.reserve(order.size());
    for (uint32_t row : order)
      spare.push_back(c[row]);
  } else {
    for (std::size_t i = 0; i < order.size(); ++i)
      spare[i] = c[order[i]];
  }
  c.swap(spare);
}
template <class T>
void permute_column(std::vector<T>& c, std::span<const uint32_t> order) {
  std::vector<T> spare;
  permute_column(c, order, spare);
}

template <class Table>
std::size_t table_bytes(Table& t) {
  std::size_t bytes = std::apply([](auto&... c) { return (column_bytes(c) + ...); }, t.columns());
  if constexpr (requires { t.optional_columns(); })
    bytes += std::apply([](auto&... c) { return (column_bytes(c) + ...); }, t.optional_columns());
  if constexpr (requires { t.part_columns(); })  // beside the rows, never permuted (csg.h)
    bytes += std::apply([](auto&... c) { return (column_bytes(c) + ...); }, t.part_columns());
  return bytes;
}

// Calls f(c) for every column of `t`, optional ones included.
template <class Table, class F>
void for_each_column(Table& t, const F& f) {
  std::apply([&](auto&... c) { (f(c), ...); }, t.columns());
  if constexpr (requires { t.optional_columns(); })
    std::apply([&](auto&... c) { (f(c), ...); }, t.optional_columns());
}

// A table's columns are permuted one at a time by each thread, each into the previous column's
// old rows (permute_column): a thread allocates one new column per column type, not one per
// column (19 columns of 5 MB for the 1.31M mesh, each a fresh mapping faulted in and an old
// one unmapped). Large tables use every thread, which take the columns one by one, so that a
// busy core delays the end by at most one column; small ones (a region costs microseconds:
// 5.7 of the course scene's 13 µs build) the calling thread, without OpenMP.
template <class Table>
void table_permute(Table& t, std::span<const uint32_t> order) {
  using Spares = std::tuple<std::vector<float>, std::vector<uint32_t>>;
  auto one = [&order](auto& c, Spares& spares) {
    permute_column(c, order, std::get<std::remove_reference_t<decltype(c)>>(spares));
  };
  if (order.size() <= 4096) {
    Spares spares;
    for_each_column(t, [&](auto& c) {
      if (!c.empty() || order.empty()) one(c, spares);  // else an optional column not in use
    });
    return;
  }
  std::vector<std::function<void(Spares&)>> jobs;
  for_each_column(t, [&](auto& c) {
    if (!c.empty()) jobs.push_back([&c, &one](Spares& spares) { one(c, spares); });
  });
  std::atomic<std::size_t> next{0};
#pragma omp parallel
  {
    Spares spares;
    for (std::size_t j = next++; j < jobs.size(); j = next++)
      jobs[j](spares);
  }
}

template <class Table>
void table_reserve(Table& t, std::size_t n) {
  std::apply([&](auto&... c) { (c.reserve(n), ...); }, t.columns());
}

}  // namespace raylane
