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

std::vector<std::vector<uint32_t>> Scene::permute(const std::vector<std::vector<uint32_t>>& order) {
  std::vector<std::vector<uint32_t>> new_row(kPrimKindCount);
  PrimKinds::for_each([&](auto kind) {
    using Kind = decltype(kind);
    const auto& o = order[kind_index<Kind>()];
    auto& nr = new_row[kind_index<Kind>()];
    nr.resize(o.size());
    for (uint32_t i = 0; i < o.size(); ++i)
      nr[o[i]] = i;
    table_permute(table<Kind>(), o);
  });
  for (PrimRef& l : lights)
    l = PrimRef(l.tag(), new_row[uint32_t(l.tag())][l.row()]);
  std::sort(lights.begin(), lights.end());
  return new_row;
}

}  // namespace raylane
