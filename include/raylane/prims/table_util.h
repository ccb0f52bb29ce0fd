// Helpers shared by the SoA tables. Every table exposes `auto columns()` (a std::tie of its
// column vectors); these work on any table through it.
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
  return std::apply([](auto&... c) { return (column_bytes(c) + ...); }, t.columns());
}

template <class Table>
void table_permute(Table& t, std::span<const uint32_t> order) {
  std::apply([&](auto&... c) { (permute_column(c, order), ...); }, t.columns());
}

template <class Table>
void table_reserve(Table& t, std::size_t n) {
  std::apply([&](auto&... c) { (c.reserve(n), ...); }, t.columns());
}

}  // namespace raylane
