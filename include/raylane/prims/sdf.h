// Signed-distance blocks: `sdf` … `end` (docs/scene-language.md, "SDF blocks").
// The table, the kind's traits and its double reference marcher (sdf.cpp); the program and the
// leaves' distances in sdf_program.h, the packet route in sdf_packet.h.
//
// As for CSG blocks (csg.h), a hit names a leaf — the one nearest the hit point, whose material
// the surface takes — as PrimRef(tag of Sdf, leaf); the BVH sees one primitive per block. The
// leaves and the blocks' slices sit beside the rows and are never permuted: a row holds its
// bounds and the index of its block in the written order (`block`), and each leaf its block's.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <tuple>
#include <vector>

#include "raylane/core/prim_ref.h"
#include "raylane/prims/box.h"
#include "raylane/prims/cylinder.h"
#include "raylane/prims/sdf_program.h"
#include "raylane/prims/sphere.h"

namespace raylane {

enum SdfLeafKind : uint32_t { kSdfSphere = 0, kSdfBox = 1, kSdfCylinder = 2, kSdfTorus = 3 };

// Tori, leaves of sdf blocks only: centre, unit axis (rounded to float), major and tube radii.
struct TorusColumns {
  std::vector<float> cx, cy, cz, ux, uy, uz, R, r;
  auto columns() { return std::tie(cx, cy, cz, ux, uy, uz, R, r); }
  std::size_t size() const { return R.size(); }
  // p = (cx, cy, cz, ax, ay, az, R, r): |a| > 0, R > 0, 0 < r ≤ R, all finite in float.
  std::optional<ParamError> append(std::span<const double, 8> p);
  Bounds3f bounds(uint32_t i) const;
};

// The march: at most kSdfMaxSteps steps; a hit where |distance| < sdf_tolerance(s, o) at the
// distance s travelled along the unit direction from an origin of max norm o. 1e-4·s is about
// a pixel's footprint at any distance (a relative error of 1e-4 in depth; 1e-3 stops far too
// early at grazing angles, where the error along the ray is the tolerance over the cosine);
// 2^-20·(o + s) is 8 float ulps of the point's largest coordinate (|p| ≤ o + s), the floor
// below which a distance computed from float coordinates is rounding noise.
inline constexpr int kSdfMaxSteps = 256;
template <class T>
T sdf_tolerance(T s, T o) {
  return T(1e-4) * s + T(0x1p-20) * (o + s);
}

// What the float marcher did (sdf_packet.h): lanes that marched a block, the distance
// evaluations they took, and those still marching after kSdfMaxSteps (misses by steps). Each
// thread adds to its own counts (no shared cache line in the kernels); sdf_march_counts sums
// them over the threads since the program started, so a caller takes the difference around
// what it measures.
struct SdfMarchCounts {
  uint64_t marches = 0, steps = 0, out_of_steps = 0;
};
void sdf_count_marches(const SdfMarchCounts& c);
SdfMarchCounts sdf_march_counts();

struct SdfTable {
  // One row per block, permuted into the BVH's leaf order like any table's rows.
  std::vector<float> lox, loy, loz, hix, hiy, hiz;  // bounds, widened by k for smooth operators
  std::vector<uint32_t> block;                      // the block, in the order written
  // Beside the rows, never permuted. Per block in the order written: its slices.
  std::vector<uint32_t> leaf_begin, leaf_count, program_begin, program_count;
  // Per leaf: its kind, its row in the kind's columns, its material and its block.
  std::vector<uint32_t> leaf_kind, leaf_row, material, leaf_block;
  std::vector<uint32_t> program;  // codes (sdf_program.h); leaf codes count from the block's
  std::vector<float> program_k;   // a smooth operator's width; 0 beside the other codes
  // The leaves' parameters, in their own kinds' columns (their material unused).
  SphereTable spheres;
  BoxTable boxes;
  CylinderTable cylinders;
  TorusColumns tori;

  auto columns() { return std::tie(lox, loy, loz, hix, hiy, hiz, block); }
  auto part_columns() {
    return std::tuple_cat(std::tie(leaf_begin, leaf_count, program_begin, program_count, leaf_kind,
                                   leaf_row, material, leaf_block, program, program_k),
                          spheres.columns(), boxes.columns(), cylinders.columns(), tori.columns());
  }
  std::size_t size() const { return block.size(); }
  std::size_t blocks() const { return leaf_begin.size(); }
  std::size_t leaves() const { return leaf_kind.size(); }
  Bounds3f bounds(uint32_t row) const {
    Bounds3f b;
    b.lo = {lox[row], loy[row], loz[row]}, b.hi = {hix[row], hiy[row], hiz[row]};
    return b;
  }
  Bounds3f leaf_bounds(uint32_t leaf) const;

  // Writing a block: its leaves and codes go straight into the columns beside the rows; the
  // open block's leaves count from open_leaf. end_block appends its row (false, and the block
  // dropped, when its bounds are empty); drop_block removes what was written since begin_block.
  void begin_block();
  template <class Kind>
  std::optional<ParamError> add_leaf(std::span<const double, Kind::param_count> p, uint32_t mat);
  std::optional<ParamError> add_torus(std::span<const double, 8> p, uint32_t mat);
  void add_code(uint32_t code, float k = 0) { program.push_back(code), program_k.push_back(k); }
  uint32_t open_leaves() const { return uint32_t(leaves() - open_leaf_); }
  bool end_block();
  void drop_block();

 private:
  void push_leaf(uint32_t kind, uint32_t row, uint32_t mat);
  std::size_t open_leaf_ = 0, open_program_ = 0;
  std::size_t open_rows_[4] = {};
};

struct Sdf {
  using Table = SdfTable;
  static constexpr std::string_view name = "sdf", plural = "sdf blocks";
  static constexpr std::string_view keyword = "";  // a block, read by its own command
  static constexpr int param_count = 0;
  static constexpr bool two_sided = false;
  // A march evaluates the program at tens of points: many primitive tests.
  static constexpr double sah_test_cost = 16.0;
  // Surfaces by surface_ref: the gradient of the block's distance.
  static constexpr bool surface_in_lanes = false;
  static constexpr bool surface_in_float_lanes = false;
  // Never an emitter (a leaf may not emit).
  static double area(const Table&, uint32_t) { return 0; }
  static AreaSample sample_area(const Table&, uint32_t, double, double, double) { return {}; }
  struct LeafHit {
    double t = std::numeric_limits<double>::infinity();
    uint32_t row = 0;    // the leaf nearest the hit point
    uint32_t steps = 0;  // steps taken (hit or not)
  };
  // The reference march of block row `row` along the ray (sdf.cpp).
  static LeafHit hit_ref(const Table& t, uint32_t row, const Rayd& ray);
};

inline double intersect_ref(const SdfTable& s, uint32_t row, const Rayd& ray) {
  return Sdf::hit_ref(s, row, ray).t;
}

// The distance of block `block` (in the order written) at p, in double; and its leaf nearest p
// (the least |distance|, the earlier on ties); and one leaf's own distance at p.
double sdf_leaf_distance_ref(const SdfTable& s, uint32_t leaf, const glm::dvec3& p);
double sdf_distance_ref(const SdfTable& s, uint32_t block, const glm::dvec3& p);
uint32_t sdf_nearest_leaf_ref(const SdfTable& s, uint32_t block, const glm::dvec3& p);

// The surface at a hit on `leaf`'s block: the normal from the distance's gradient (Quilez's
// tetrahedron of samples, the step the hit tolerance), the point moved onto the surface along it.
Surface surface_ref(const SdfTable& s, uint32_t leaf, const Rayd& ray, double t);
inline TexCoord texcoord_ref(const SdfTable&, uint32_t, const Surface&) {
  return {};
}

template <class Kind>
std::optional<ParamError> SdfTable::add_leaf(std::span<const double, Kind::param_count> p,
                                             uint32_t mat) {
  if constexpr (std::is_same_v<Kind, Sphere>) {
    if (auto err = spheres.append(p, mat)) return err;
    push_leaf(kSdfSphere, uint32_t(spheres.size() - 1), mat);
  } else if constexpr (std::is_same_v<Kind, Box>) {
    if (auto err = boxes.append(p, mat)) return err;
    push_leaf(kSdfBox, uint32_t(boxes.size() - 1), mat);
  } else {
    static_assert(std::is_same_v<Kind, Cylinder>);
    if (auto err = cylinders.append(p, mat)) return err;
    push_leaf(kSdfCylinder, uint32_t(cylinders.size() - 1), mat);
  }
  return std::nullopt;
}

}  // namespace raylane
