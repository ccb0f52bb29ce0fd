// Axis-aligned boxes: `box bx by bz dx dy dz` (corner b, diagonal d). The table, the kind's traits
// and its reference kernel; the SIMD kernel is in box_packet.h.
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
#include "raylane/core/prim_ref.h"
#include "raylane/prims/solid.h"
#include "raylane/prims/surface.h"
#include "raylane/prims/table_util.h"

namespace raylane {

// Stored as its min and max corners (docs/hard-cases.md B1: a negative diagonal is the same box).
struct BoxTable {
  std::vector<float> lox, loy, loz, hix, hiy, hiz;
  std::vector<uint32_t> material;

  auto columns() { return std::tie(lox, loy, loz, hix, hiy, hiz, material); }
  std::size_t size() const { return lox.size(); }
  glm::vec3 lo(uint32_t i) const { return {lox[i], loy[i], loz[i]}; }
  glm::vec3 hi(uint32_t i) const { return {hix[i], hiy[i], hiz[i]}; }

  // p = (bx, by, bz, dx, dy, dz); every component of d must be non-zero, and stay so after
  // both corners are rounded to float; both corners must be finite floats.
  std::optional<ParamError> append(std::span<const double, 6> p, uint32_t mat) {
    float a[3], b[3];
    for (int k = 0; k < 3; ++k) {
      if (p[3 + k] == 0.0) return ParamError{3 + k, "box diagonal components must be non-zero"};
      a[k] = float(std::min(p[k], p[k] + p[3 + k]));
      b[k] = float(std::max(p[k], p[k] + p[3 + k]));
      if (!std::isfinite(a[k]) || !std::isfinite(b[k]))
        return ParamError{3 + k, "box corner lies beyond float (the largest is about 3.4e38)"};
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
  using Table = BoxTable;
  static constexpr std::string_view name = "box", plural = "boxes", keyword = "box";
  static constexpr int param_count = 6;
  static constexpr bool two_sided = false;
  static constexpr double sah_test_cost = 1.0;
  // The SIMD tracer computes its hits' surfaces in double lanes (box_packet.h, surface_lanes).
  static constexpr bool surface_in_lanes = true;
  static double area(const Table& t, uint32_t i);
  // A uniform point on the surface and its outward normal; u_part picks the part (a box's
  // face, a cylinder's side or cap) in proportion to its area.
  static AreaSample sample_area(const Table& t, uint32_t i, double u_part, double u1, double u2);
};

namespace detail {
// The slab intervals of one axis: near and far t, chosen by the sign bit of d so that +0 and
// −0 agree (docs/hard-cases.md B3). A ray lying in a slab plane gives 0·inf = NaN, which the
// callers' comparisons skip: the closed-box answer (B4).
inline void box_slab(double lo, double hi, double o, double d, double& tn, double& tf) {
  double inv = 1.0 / d;
  bool neg = std::signbit(d);
  tn = ((neg ? hi : lo) - o) * inv;
  tf = ((neg ? lo : hi) - o) * inv;
}
}  // namespace detail

// The reference kernel: the slab method (Kay and Kajiya 1986) in double, closed box. The
// running extrema keep their value when a slab value is NaN (`t0 = tn > t0 ? tn : t0`).
inline double intersect_ref(const BoxTable& b, uint32_t i, const Rayd& ray) {
  glm::dvec3 lo(b.lo(i)), hi(b.hi(i));
  double t0 = -std::numeric_limits<double>::infinity(), t1 = -t0;
  for (int k = 0; k < 3; ++k) {
    double tn, tf;
    detail::box_slab(lo[k], hi[k], ray.o[k], ray.d[k], tn, tf);
    t0 = tn > t0 ? tn : t0;
    t1 = tf < t1 ? tf : t1;
  }
  if (!(t0 <= t1)) return std::numeric_limits<double>::infinity();
  return first_in_range(t0, t1, ray);
}

// The face: at the entry, the axis whose near plane is last (the largest near t); at the
// exit, the axis whose far plane is first; ties go to the lowest axis, so the normal is
// always exactly one unit axis vector (docs/hard-cases.md B5). The point is snapped onto that face.
inline Surface surface_ref(const BoxTable& b, uint32_t i, const Rayd& ray, double t) {
  glm::dvec3 lo(b.lo(i)), hi(b.hi(i));
  double tn[3], tf[3];
  for (int k = 0; k < 3; ++k)
    detail::box_slab(lo[k], hi[k], ray.o[k], ray.d[k], tn[k], tf[k]);
  double entry = -std::numeric_limits<double>::infinity();
  int entry_axis = -1, exit_axis = -1;
  double exit = std::numeric_limits<double>::infinity();
  // Selects, not branches: which axis wins is data the branch predictor cannot learn (a
  // render's hits land on every face), and this runs for every hit on a box.
  for (int k = 0; k < 3; ++k) {
    bool nearer = tn[k] > entry, farther = tf[k] < exit;
    entry = nearer ? tn[k] : entry;
    entry_axis = nearer ? k : entry_axis;
    exit = farther ? tf[k] : exit;
    exit_axis = farther ? k : exit_axis;
  }
  // The nearer end of the interval: t may come from a float kernel, so never compare exactly.
  bool entering =
      (entry_axis >= 0) & ((exit_axis < 0) | (std::abs(t - entry) <= std::abs(t - exit)));
  int axis = entering ? entry_axis : (exit_axis >= 0 ? exit_axis : 0);
  bool neg = std::signbit(ray.d[axis]);
  glm::dvec3 n(0, 0, 0), p = ray.at(t);
  // Entering, the face looks back at the ray; leaving, it looks along it.
  n[axis] = (entering == neg) ? 1.0 : -1.0;
  p[axis] = n[axis] > 0 ? hi[axis] : lo[axis];
  return {p, n, n};
}

// On the face normal to axis k, u and v run 0 → 1 across it along the other two axes in x, y, z
// order (normal to x: u along y, v along z; to y: x, z; to z: x, y).
inline TexCoord texcoord_ref(const BoxTable& b, uint32_t i, const Surface& s) {
  glm::dvec3 lo(b.lo(i)), hi(b.hi(i));
  int k = s.ng.x != 0 ? 0 : (s.ng.y != 0 ? 1 : 2);
  int a = k == 0 ? 1 : 0, c = k == 2 ? 1 : 2;
  auto across = [&](int axis) { return (s.p[axis] - lo[axis]) / (hi[axis] - lo[axis]); };
  return {across(a), across(c)};
}

}  // namespace raylane
