// Helpers shared by the SoA tables. Every table exposes `auto columns()` (a std::tie of its
// column vectors); these work on any table through it. A table may also have optional columns
// (`auto optional_columns()`), empty unless a scene needs them (mesh UVs): they are permuted
// and counted when they hold rows, and never reserved ahead.
#pragma once

#include <cstddef>
#include <cstdint>
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
  return bytes;
}

// Large tables are permuted one column per OpenMP task (the BVH build permutes every table
// once: 19 columns of triangles), in one parallel region, so that a busy core delays the
// region's end by at most one column. Small ones in the calling thread, without OpenMP (a
// region and its tasks cost microseconds: 5.7 of the course scene's 13 µs build), each column
// written into the previous one's old rows (permute_column).
template <class Table>
void table_permute(Table& t, std::span<const uint32_t> order) {
  if (order.size() <= 4096) {
    std::tuple<std::vector<float>, std::vector<uint32_t>> spares;
    auto one = [&](auto& c) {
      if (c.empty() && order.size() > 0) return;  // an optional column the table does not use
      permute_column(c, order, std::get<std::remove_reference_t<decltype(c)>>(spares));
    };
    std::apply([&](auto&... c) { (one(c), ...); }, t.columns());
    if constexpr (requires { t.optional_columns(); })
      std::apply([&](auto&... c) { (one(c), ...); }, t.optional_columns());
    return;
  }
  auto one = [&](auto& c) {
    if (c.empty()) return;  // an optional column the table does not use
    auto* column = &c;
    std::span<const uint32_t> rows = order;
#pragma omp task firstprivate(column, rows)
    permute_column(*column, rows);
  };
#pragma omp parallel
#pragma omp single
  {
    std::apply([&](auto&... c) { (one(c), ...); }, t.columns());
    if constexpr (requires { t.optional_columns(); })
      std::apply([&](auto&... c) { (one(c), ...); }, t.optional_columns());
  }
}

template <class Table>
void table_reserve(Table& t, std::size_t n) {
  std::apply([&](auto&... c) { (c.reserve(n), ...); }, t.columns());
}

}  // namespace raylane
