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
#include "raylane/core/float_util.h"
#include "raylane/core/numbers.h"
#include "raylane/core/prim_ref.h"
#include "raylane/core/ray.h"
#include "raylane/core/ray_offset.h"
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
  // The render's float columns take its surfaces in float lanes, with their error bounds
  // (box_packet.h, surface_float_lanes).
  static constexpr bool surface_in_float_lanes = true;
  static double area(const Table& t, uint32_t i);
  // A uniform point on the surface and its outward normal; u_part picks the part (a box's
  // face, a cylinder's side or cap) in proportion to its area.
  static AreaSample sample_area(const Table& t, uint32_t i, double u_part, double u1, double u2);
  // A box emits from its outside only, and from a point outside it at most three faces face
  // the point (one per axis: the hi face where the point is beyond hi, the lo face where it is
  // below lo). Light sampling draws from those alone, by area: the other faces' samples would
  // be wasted (no emission toward the point), and the area those faces leave out is the only
  // part of the density that changes (area_seen_from is the denominator of the density by
  // area, for the sample and for MIS alike). 0 where no face faces the point: in the closed
  // box. The steps are prims/box_faces.h's.
  static double area_seen_from(const Table& t, uint32_t i, const glm::dvec3& ref);
  // A uniform point on the faces that face `ref`, u_part picking the face in proportion to
  // its area, and its outward normal; a zero normal where none does.
  static AreaSample sample_area_seen_from(const Table& t, uint32_t i, const glm::dvec3& ref,
                                          double u_part, double u1, double u2);
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

// The surface at a hit, written once over the number type N (core/numbers.h) and its 3-vector
// V3: double for surface_ref, double lanes for the SIMD tracer's hit records, float lanes for the
// render's float columns (box_packet.h). The face: at the entry, the axis whose near plane is
// last (the largest near t); at the exit, the axis whose far plane is first; ties go to the
// lowest axis, so the normal is always exactly one unit axis vector (docs/hard-cases.md B5).
// The point o + t·d is snapped onto that face. Selects, not branches: which axis wins is data
// the branch predictor cannot learn (a render's hits land on every face).
template <class V3>
struct BoxSurface {
  V3 p, n;
};
// Inlined always: a call passes the lanes through memory (GCC kept it out of line in the
// render's surface pass, spilling every operand). The axes are spelled out by value, not
// walked through arrays of pointers to the vectors' members: pointers kept the point and the
// normal in memory, and GCC copied them there and back piece by piece.
template <class N, class V3>
[[gnu::always_inline]] inline BoxSurface<V3> box_surface(const V3& lo, const V3& hi, const V3& o,
                                                         const V3& d, const N& t) {
  using K = Num<N>;
  N entry(-HUGE_VAL), exit(HUGE_VAL), entry_axis(-1.0), exit_axis(-1.0);
  auto slab = [&](const N& lo_k, const N& hi_k, const N& o_k, const N& d_k, double k) {
    const N inv = N(1.0) / d_k;  // detail::box_slab's steps
    const auto neg = K::sign_bit(d_k);
    const N tn = (K::select(neg, hi_k, lo_k) - o_k) * inv;
    const N tf = (K::select(neg, lo_k, hi_k) - o_k) * inv;
    const auto nearer = tn > entry, farther = tf < exit;
    entry = K::select(nearer, tn, entry);
    entry_axis = K::select(nearer, N(k), entry_axis);
    exit = K::select(farther, tf, exit);
    exit_axis = K::select(farther, N(k), exit_axis);
  };
  slab(lo.x, hi.x, o.x, d.x, 0.0), slab(lo.y, hi.y, o.y, d.y, 1.0);
  slab(lo.z, hi.z, o.z, d.z, 2.0);
  // The nearer end of the interval: t may come from a float kernel, so never compare exactly.
  const auto entering =
      (entry_axis >= N(0.0)) & ((exit_axis < N(0.0)) | (K::abs(t - entry) <= K::abs(t - exit)));
  const N axis = K::select(entering, entry_axis, K::select(exit_axis >= N(0.0), exit_axis, N(0.0)));
  // Entering, the face looks back at the ray; leaving, it looks along it.
  auto sign = [&](const N& d_k) {
    const auto neg = K::sign_bit(d_k);
    return K::select(entering, K::select(neg, N(1.0), N(-1.0)), K::select(neg, N(-1.0), N(1.0)));
  };
  const N sx = sign(d.x), sy = sign(d.y), sz = sign(d.z);
  auto normal = [&](const N& sign_k, double k) { return K::select(axis == N(k), sign_k, N(0.0)); };
  // The point o + t·d, snapped onto the face's plane on its axis.
  auto point = [&](const N& lo_k, const N& hi_k, const N& o_k, const N& d_k, const N& sign_k,
                   double k) {
    return K::select(axis == N(k), K::select(sign_k > N(0.0), hi_k, lo_k), o_k + d_k * t);
  };
  return {V3{point(lo.x, hi.x, o.x, d.x, sx, 0.0), point(lo.y, hi.y, o.y, d.y, sy, 1.0),
             point(lo.z, hi.z, o.z, d.z, sz, 2.0)},
          V3{normal(sx, 0.0), normal(sy, 1.0), normal(sz, 2.0)}};
}

// A bound on the error of box_surface's point computed in float, for the offset along its
// normal. On the face's axis the point is the face's own float plane, exact; the bound keeps
// one roundoff of the box's larger corner coordinate on that axis there, so that an origin
// offset by it moves off the plane even where the face lies at 0 (the course scene's floor),
// and a ray leaving within the face's plane (a direction component ±0) starts outside the slab
// rather than on it, where 0·inf is NaN and the slab would not count. Along the face the point
// is o + t·d, as float_hit_point_bound (core/ray_offset.h) bounds it.
template <class N, class V3>
V3 box_point_bound(const V3& lo, const V3& hi, const V3& o, const V3& d, const N& t,
                   const BoxSurface<V3>& s) {
  using K = Num<N>;
  const V3 along = float_hit_point_bound<N>(o, d, t, s.p);
  const N own(kFloatUnitRoundoff * (1 + 0x1p-20));
  auto one = [&](const N& nk, const N& lok, const N& hik, const N& ak) {
    return K::select(nk != N(0.0), K::max(K::abs(lok), K::abs(hik)) * own, ak);
  };
  return V3{one(s.n.x, lo.x, hi.x, along.x), one(s.n.y, lo.y, hi.y, along.y),
            one(s.n.z, lo.z, hi.z, along.z)};
}

inline Surface surface_ref(const BoxTable& b, uint32_t i, const Rayd& ray, double t) {
  const BoxSurface<glm::dvec3> x =
      box_surface<double>(glm::dvec3(b.lo(i)), glm::dvec3(b.hi(i)), ray.o, ray.d, t);
  return {x.p, x.n, x.n};
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
