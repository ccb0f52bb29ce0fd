// Spheres: `sphere cx cy cz r`. The table, its reference kernel and its packet kernel.
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

struct SphereTable {
  std::vector<float> cx, cy, cz, r;
  std::vector<uint32_t> material;

  auto columns() { return std::tie(cx, cy, cz, r, material); }
  std::size_t size() const { return r.size(); }
  Vec3f center(uint32_t i) const { return {cx[i], cy[i], cz[i]}; }

  // p = (cx, cy, cz, r); r must be > 0 after rounding to float.
  std::optional<ParamError> append(std::span<const double, 4> p, uint32_t mat) {
    float radius = float(p[3]);
    if (!(radius > 0.0f)) return ParamError{3, "sphere radius must be > 0"};
    cx.push_back(float(p[0]));
    cy.push_back(float(p[1]));
    cz.push_back(float(p[2]));
    r.push_back(radius);
    material.push_back(mat);
    return std::nullopt;
  }

  Bounds3f bounds(uint32_t i) const {
    Vec3d c(center(i));
    Vec3d rr(r[i], r[i], r[i]);
    return round_out(Bounds3d(c - rr, c + rr));
  }
};

struct Sphere {
  static constexpr PrimTag tag = PrimTag::kSphere;
  static constexpr std::string_view keyword = "sphere";
  static constexpr int param_count = 4;
  using Table = SphereTable;
};

}  // namespace raylane
