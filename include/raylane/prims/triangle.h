// Mesh triangles (made by the `mesh` command). The table, its reference kernel and its
// packet kernel.
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

// Vertices as given (the watertight test works on vertices relative to the ray origin, so it
// wants p0, p1, p2 rather than edges), and per-vertex shading normals.
struct TriangleTable {
  std::vector<float> p0x, p0y, p0z, p1x, p1y, p1z, p2x, p2y, p2z;
  std::vector<float> n0x, n0y, n0z, n1x, n1y, n1z, n2x, n2y, n2z;
  std::vector<uint32_t> material;

  auto columns() {
    return std::tie(p0x, p0y, p0z, p1x, p1y, p1z, p2x, p2y, p2z, n0x, n0y, n0z, n1x, n1y, n1z,
                    n2x, n2y, n2z, material);
  }
  std::size_t size() const { return p0x.size(); }
  Vec3f p0(uint32_t i) const { return {p0x[i], p0y[i], p0z[i]}; }
  Vec3f p1(uint32_t i) const { return {p1x[i], p1y[i], p1z[i]}; }
  Vec3f p2(uint32_t i) const { return {p2x[i], p2y[i], p2z[i]}; }
  Vec3f n0(uint32_t i) const { return {n0x[i], n0y[i], n0z[i]}; }
  Vec3f n1(uint32_t i) const { return {n1x[i], n1y[i], n1z[i]}; }
  Vec3f n2(uint32_t i) const { return {n2x[i], n2y[i], n2z[i]}; }

  void append(const std::array<Vec3f, 3>& p, const std::array<Vec3f, 3>& n, uint32_t mat) {
    p0x.push_back(p[0].x), p0y.push_back(p[0].y), p0z.push_back(p[0].z);
    p1x.push_back(p[1].x), p1y.push_back(p[1].y), p1z.push_back(p[1].z);
    p2x.push_back(p[2].x), p2y.push_back(p[2].y), p2z.push_back(p[2].z);
    n0x.push_back(n[0].x), n0y.push_back(n[0].y), n0z.push_back(n[0].z);
    n1x.push_back(n[1].x), n1y.push_back(n[1].y), n1z.push_back(n[1].z);
    n2x.push_back(n[2].x), n2y.push_back(n[2].y), n2z.push_back(n[2].z);
    material.push_back(mat);
  }

  // Vertices are exact floats: their min and max need no rounding.
  Bounds3f bounds(uint32_t i) const {
    Bounds3f b;
    b.extend(p0(i));
    b.extend(p1(i));
    b.extend(p2(i));
    return b;
  }
};

struct Triangle {
  static constexpr PrimTag tag = PrimTag::kTriangle;
  static constexpr std::string_view keyword = "";  // no scene command: made by `mesh`
  static constexpr int param_count = 0;
  using Table = TriangleTable;
};

}  // namespace raylane
