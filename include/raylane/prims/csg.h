// CSG blocks: `csg` … `end` (docs/scene-language.md, "CSG blocks"). The table, the
// kind's traits and its reference kernel; the SIMD kernel is in csg_packet.h, the program in
// csg_program.h.
//
// A hit on a block names the leaf whose surface it is, not the block: PrimRef(tag of Csg, leaf),
// the leaf's index in the table's flat leaf columns. So a hit's material (Scene::material_of),
// surface and texture coordinates are the leaf's, read from columns indexed by leaf; the BVH
// sees one primitive per block (size() and bounds() count blocks).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "raylane/core/prim_ref.h"
#include "raylane/prims/box.h"
#include "raylane/prims/csg_program.h"
#include "raylane/prims/cylinder.h"
#include "raylane/prims/sphere.h"

namespace raylane {

// The leaf kinds, as CsgTable::leaf_kind stores them.
enum CsgLeafKind : uint32_t { kCsgSphere = 0, kCsgBox = 1, kCsgCylinder = 2 };

struct CsgTable {
  // One row per block, permuted into the BVH's leaf order like any table's rows.
  std::vector<float> lox, loy, loz, hix, hiy, hiz;     // bounds, by the spec's rule
  std::vector<uint32_t> leaf_begin, leaf_count;        // its leaves: a slice of leaf_*
  std::vector<uint32_t> program_begin, program_count;  // its postfix program: a slice
  // Beside the rows, never permuted (a row's slices stay valid): every block's leaves in order.
  std::vector<uint32_t> leaf_kind;  // CsgLeafKind
  std::vector<uint32_t> leaf_row;   // the leaf's row in spheres, boxes or cylinders
  std::vector<uint32_t> material;   // per leaf, since a hit names its leaf
  std::vector<uint32_t> leaf_flip;  // 1: the leaf's surface bounds the solid inside out
  std::vector<uint32_t> program;    // codes (csg_program.h); leaf codes count from the block's
  // The leaves' parameters, in the columns of their own kinds' tables (their material unused).
  SphereTable spheres;
  BoxTable boxes;
  CylinderTable cylinders;

  auto columns() {
    return std::tie(lox, loy, loz, hix, hiy, hiz, leaf_begin, leaf_count, program_begin,
                    program_count);
  }
  // The columns beside the rows: hashed with the scene, counted by `raylane info`.
  auto part_columns() {
    return std::tuple_cat(std::tie(leaf_kind, leaf_row, material, leaf_flip, program),
                          spheres.columns(), boxes.columns(), cylinders.columns());
  }
  std::size_t size() const { return leaf_begin.size(); }
  std::size_t leaves() const { return leaf_kind.size(); }
  std::span<const uint32_t> program_of(uint32_t i) const {
    return {program.data() + program_begin[i], program_count[i]};
  }
  Bounds3f bounds(uint32_t i) const {
    Bounds3f b;
    b.lo = {lox[i], loy[i], loz[i]}, b.hi = {hix[i], hiy[i], hiz[i]};
    return b;
  }
  Bounds3f leaf_bounds(uint32_t leaf) const;

  // A block being written (the parser's draft: leaves and program, no rows yet). Leaf
  // parameters are validated by the leaf's own kind.
  template <class Kind>
  std::optional<ParamError> add_leaf(std::span<const double, Kind::param_count> p, uint32_t mat);
  void add_code(uint32_t code) { program.push_back(code); }

  // Appends the draft's block as a row: false, and nothing appended, when its bounds are empty
  // (an intersection of disjoint leaves: the solid is empty).
  bool append_block(CsgTable& draft);
};

struct Csg {
  using Table = CsgTable;
  static constexpr std::string_view name = "csg", plural = "csg blocks";
  static constexpr std::string_view keyword = "";  // a block, read by its own command
  static constexpr int param_count = 0;
  static constexpr bool two_sided = false;
  // A block tests each leaf's interval and walks their events: a few primitive tests.
  static constexpr double sah_test_cost = 2.0;
  // Surfaces by surface_ref: a hit is a leaf, whose kind decides the surface.
  static constexpr bool surface_in_lanes = false;
  static constexpr bool surface_in_float_lanes = false;
  // Never an emitter (a leaf may not emit): these exist for the kind list's interface.
  static double area(const Table&, uint32_t) { return 0; }
  static AreaSample sample_area(const Table&, uint32_t, double, double, double) { return {}; }
  // The reference hit: t and the leaf it names (csg.cpp).
  struct LeafHit {
    double t = std::numeric_limits<double>::infinity();
    uint32_t row = 0;
  };
  static LeafHit hit_ref(const Table& t, uint32_t block, const Rayd& ray);
};

inline double intersect_ref(const CsgTable& c, uint32_t block, const Rayd& ray) {
  return Csg::hit_ref(c, block, ray).t;
}

// Leaf `leaf`'s interval on the ray's line, in double, by its kind's reference; an empty one is
// (+inf, +inf), which holds no point and whose ends are never events beyond a finite tmin.
void csg_leaf_interval_ref(const CsgTable& c, uint32_t leaf, const Rayd& ray, double& t0,
                           double& t1);

// The leaf's own surface, its normals turned where the leaf bounds a subtracted solid.
Surface surface_ref(const CsgTable& c, uint32_t leaf, const Rayd& ray, double t);
TexCoord texcoord_ref(const CsgTable& c, uint32_t leaf, const Surface& s);

template <class Kind>
std::optional<ParamError> CsgTable::add_leaf(std::span<const double, Kind::param_count> p,
                                             uint32_t mat) {
  static_assert(std::is_same_v<Kind, Sphere> || std::is_same_v<Kind, Box> ||
                std::is_same_v<Kind, Cylinder>);
  if (leaf_kind.size() >= kCsgMaxLeaves)
    return ParamError{-1, "a csg block holds at most 64 leaves"};
  auto& t = [this]() -> typename Kind::Table& {
    if constexpr (std::is_same_v<Kind, Sphere>)
      return spheres;
    else if constexpr (std::is_same_v<Kind, Box>)
      return boxes;
    else
      return cylinders;
  }();
  if (auto err = t.append(p, mat)) return err;
  leaf_kind.push_back(std::is_same_v<Kind, Sphere> ? kCsgSphere
                      : std::is_same_v<Kind, Box>  ? kCsgBox
                                                   : kCsgCylinder);
  leaf_row.push_back(uint32_t(t.size() - 1));
  material.push_back(mat);
  leaf_flip.push_back(0);
  program.push_back(uint32_t(leaf_kind.size() - 1));
  return std::nullopt;
}

}  // namespace raylane
