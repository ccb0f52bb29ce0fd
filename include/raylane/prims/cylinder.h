// Capped cylinders: `cylinder bx by bz ax ay az r` (base centre b, axis a from base to top
// cap, radius r). The table, its reference kernel and its packet kernel.
#pragma once

#include <array>
#include <cmath>
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

// The defining values (base, axis, radius) as given, rounded to float, plus the derived unit
// axis and height, computed once in double from those floats (hard-cases.md C6).
struct CylinderTable {
  std::vector<float> bx, by, bz;  // base centre
  std::vector<float> ax, ay, az;  // axis: base to top-cap centre
  std::vector<float> r;
  std::vector<float> ux, uy, uz;  // derived: unit axis
  std::vector<float> h;           // derived: |axis|
  std::vector<uint32_t> material;

  auto columns() { return std::tie(bx, by, bz, ax, ay, az, r, ux, uy, uz, h, material); }
  std::size_t size() const { return r.size(); }
  Vec3f base(uint32_t i) const { return {bx[i], by[i], bz[i]}; }
  Vec3f axis(uint32_t i) const { return {ax[i], ay[i], az[i]}; }
  Vec3f unit_axis(uint32_t i) const { return {ux[i], uy[i], uz[i]}; }

  // p = (bx, by, bz, ax, ay, az, r); |a| > 0 and r > 0 after rounding to float.
  std::optional<ParamError> append(std::span<const double, 7> p, uint32_t mat) {
    Vec3f a{float(p[3]), float(p[4]), float(p[5])};
    Vec3d ad(a);
    double len = length(ad);
    if (!(len > 0.0)) return ParamError{3, "cylinder axis must be non-zero"};
    if (!std::isfinite(len)) return ParamError{3, "cylinder axis is too long"};
    float radius = float(p[6]);
    if (!(radius > 0.0f)) return ParamError{6, "cylinder radius must be > 0"};
    Vec3d u = ad / len;
    bx.push_back(float(p[0]));
    by.push_back(float(p[1]));
    bz.push_back(float(p[2]));
    ax.push_back(a.x);
    ay.push_back(a.y);
    az.push_back(a.z);
    r.push_back(radius);
    ux.push_back(float(u.x));
    uy.push_back(float(u.y));
    uz.push_back(float(u.z));
    h.push_back(float(len));
    material.push_back(mat);
    return std::nullopt;
  }

  // The box of the two cap discs: the span of both centres grown by r·sqrt(1 − u_k²) per
  // axis (hard-cases.md C7), computed in double and rounded outward.
  Bounds3f bounds(uint32_t i) const {
    Vec3d b(base(i)), top = Vec3d(base(i)) + Vec3d(axis(i));
    Vec3d u = normalize(Vec3d(axis(i)));
    double rad = r[i];
    Vec3d g(rad * std::sqrt(std::max(0.0, 1 - u.x * u.x)),
            rad * std::sqrt(std::max(0.0, 1 - u.y * u.y)),
            rad * std::sqrt(std::max(0.0, 1 - u.z * u.z)));
    Bounds3d bb(b, top);
    return round_out(Bounds3d(bb.lo - g, bb.hi + g));
  }
};

struct Cylinder {
  static constexpr PrimTag tag = PrimTag::kCylinder;
  static constexpr std::string_view keyword = "cylinder";
  static constexpr int param_count = 7;
  using Table = CylinderTable;
};

}  // namespace raylane
