#include "raylane/scene/scene.h"

#include <algorithm>

namespace raylane {

std::size_t Scene::primitive_count() const {
  std::size_t n = 0;
  std::apply([&](const auto&... t) { n = (t.size() + ...); }, tables);
  return n;
}

uint32_t Scene::material_of(PrimRef ref) const {
  return dispatch(ref.tag(), [&](auto kind) -> uint32_t {
    return table<decltype(kind)>().material[ref.row()];
  });
}

Bounds3f Scene::bounds() const {
  Bounds3f b;
  PrimKinds::for_each([&](auto kind) {
    const auto& t = table<decltype(kind)>();
    for (uint32_t i = 0; i < t.size(); ++i)
      b.extend(t.bounds(i));
  });
  return b;
}

void Scene::permute(const std::vector<std::vector<uint32_t>>& order) {
  // The new row of every old row, for the kinds that have lights only (for the others it
  // would be a table-sized pass that nothing reads: 4 ms of the 1.31M mesh's build).
  std::vector<std::vector<uint32_t>> new_row(kPrimKindCount);
  for (PrimRef l : lights) {
    const uint32_t k = uint32_t(l.tag());
    if (!new_row[k].empty()) continue;
    new_row[k].resize(order[k].size());
    for (uint32_t i = 0; i < order[k].size(); ++i)
      new_row[k][order[k][i]] = i;
  }
  PrimKinds::for_each([&](auto kind) {
    using Kind = decltype(kind);
    table_permute(table<Kind>(), order[kind_index<Kind>()]);
  });
  for (PrimRef& l : lights)
    l = PrimRef(l.tag(), new_row[uint32_t(l.tag())][l.row()]);
  std::sort(lights.begin(), lights.end());
}

}  // namespace raylane
