// Axis-aligned boxes: `box bx by bz dx dy dz` (corner b, diagonal d). The table, its
// reference kernel and its packet kernel.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "raylane/core/bounds3.h"
#include "raylane/core/ray.h"
#include "raylane/prims/prim_ref.h"
#include "raylane/prims/surface.h"
#include "raylane/prims/table_util.h"

namespace raylane {

// Stored as its min and max corners (hard-cases.md B1: a negative diagonal is the same box).
struct BoxTable {
  std::vector<float> lox, loy, loz, hix, hiy, hiz;
  std::vector<uint32_t> material;

  auto columns() { return std::tie(lox, loy, loz, hix, hiy, hiz, material); }
  std::size_t size() const { return lox.size(); }
  Vec3f lo(uint32_t i) const { return {lox[i], loy[i], loz[i]}; }
  Vec3f hi(uint32_t i) const { return {hix[i], hiy[i], hiz[i]}; }

  // p = (bx, by, bz, dx, dy, dz); every component of d must be non-zero, and stay so after
  // both corners are rounded to float.
  std::optional<ParamError> append(std::span<const double, 6> p, uint32_t mat) {
    float a[3], b[3];
    for (int k = 0; k < 3; ++k) {
      if (p[3 + k] == 0.0) return ParamError{3 + k, "box diagonal components must be non-zero"};
      a[k] = float(std::min(p[k], p[k] + p[3 + k]));
      b[k] = float(std::max(p[k], p[k] + p[3 + k]));
      if (!(a[k] < b[k]))
        return ParamError{3 + k, "box is thinner than float precision along this axis"};
    }
    lox.push_back(a[0]);
    loy.push_back(a[1]);
    loz.push_back(a[2]);
    hix.push_back(b[0]);
    hiy.push_back(b[1]);
    hiz.push_back(b[2]);
    material.push_back(mat);
    return std::nullopt;
  }

  // The stored corners are exact floats: no rounding needed.
  Bounds3f bounds(uint32_t i) const { return Bounds3f(lo(i), hi(i)); }
};

struct Box {
  static constexpr PrimTag tag = PrimTag::kBox;
  static constexpr std::string_view keyword = "box";
  static constexpr int param_count = 6;
  using Table = BoxTable;
};

}  // namespace raylane
