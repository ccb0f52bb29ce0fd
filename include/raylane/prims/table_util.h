// Helpers shared by the SoA tables. Every table exposes `auto columns()` (a std::tie of its
// column vectors); these work on any table through it. A table may also have optional columns
// (`auto optional_columns()`), empty unless a scene needs them (mesh UVs): they are permuted
// and counted when they hold rows, and never reserved ahead.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <tuple>
#include <vector>

namespace raylane {

template <class T>
std::size_t column_bytes(const std::vector<T>& c) {
  return c.size() * sizeof(T);
}

// Reorders a column so that new row i is old row order[i].
template <class T>
void permute_column(std::vector<T>& c, std::span<const uint32_t> order) {
  std::vector<T> out(order.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    out[i] = c[order[i]];
  c.swap(out);
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
// region's end by at most one column.
template <class Table>
void table_permute(Table& t, std::span<const uint32_t> order) {
  auto one = [&](auto& c) {
    if (c.empty() && order.size() > 0) return;  // an optional column the table does not use
    auto* column = &c;
    std::span<const uint32_t> rows = order;
#pragma omp task firstprivate(column, rows)
    permute_column(*column, rows);
  };
#pragma omp parallel if (order.size() > 32768)
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
