// Capped cylinders: `cylinder bx by bz ax ay az r` (base centre b, axis a from base to top
// cap, radius r). The table, the kind's traits and its reference kernel; the SIMD kernel is in
// cylinder_packet.h.
#pragma once

#include <algorithm>
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
#include "raylane/core/warps.h"
#include "raylane/prims/solid.h"
#include "raylane/prims/surface.h"
#include "raylane/prims/table_util.h"

namespace raylane {

// A cylinder is stored as base b, unit axis u, height h and radius r, in float: u and h are
// computed once in double from the given axis rounded to float (docs/hard-cases.md C6) and
// rounded to float, and the axis is u·h, which double holds exactly (two 24-bit significands).
// The float kernel reads b, u, h, r; the reference, the bounds and the surfaces take the same
// u·h in double, so all of them see one cylinder. Not storing the given axis as well saves 12
// of a row's 36 bytes (bench/README.md, "The lattice's bytes per primitive, the 8-wide collapse
// by least visits"); the cylinder then differs from one through the given float axis by the
// rounding of u and h, a few ulps of |a|.
struct CylinderTable {
  std::vector<float> bx, by, bz;  // base centre
  std::vector<float> r;
  std::vector<float> ux, uy, uz;  // unit axis, rounded
  std::vector<float> h;           // |axis|, rounded
  std::vector<uint32_t> material;

  auto columns() { return std::tie(bx, by, bz, r, ux, uy, uz, h, material); }
  std::size_t size() const { return r.size(); }
  glm::vec3 base(uint32_t i) const { return {bx[i], by[i], bz[i]}; }
  // Base to top-cap centre, exactly u·h.
  glm::dvec3 axis(uint32_t i) const { return glm::dvec3(unit_axis(i)) * double(h[i]); }
  glm::vec3 unit_axis(uint32_t i) const { return {ux[i], uy[i], uz[i]}; }

  // p = (bx, by, bz, ax, ay, az, r); |a| > 0 and r > 0 after rounding to float, and the
  // caps grown by r finite in float.
  std::optional<ParamError> append(std::span<const double, 7> p, uint32_t mat) {
    glm::vec3 a{float(p[3]), float(p[4]), float(p[5])};
    glm::dvec3 ad(a);
    double len = length(ad);
    if (!(len > 0.0)) return ParamError{3, "cylinder axis must be non-zero"};
    if (!std::isfinite(float(len))) return ParamError{3, "cylinder axis is too long"};
    float radius = float(p[6]);
    if (!(radius > 0.0f))
      return ParamError{6, p[6] > 0 ? "cylinder radius rounds to 0 in single precision; it must "
                                      "be > 0 after rounding (at least about 1.4e-45)"
                                    : "cylinder radius must be > 0"};
    for (int k = 0; k < 3; ++k)  // its bounds, both caps grown by r, must be finite floats
      if (!std::isfinite(float(std::abs(p[k]) + std::abs(double(a[k])) + double(radius))))
        return ParamError{3, "cylinder reaches beyond float (the largest is about 3.4e38)"};
    glm::dvec3 u = ad / len;
    bx.push_back(float(p[0]));
    by.push_back(float(p[1]));
    bz.push_back(float(p[2]));
    r.push_back(radius);
    ux.push_back(float(u.x));
    uy.push_back(float(u.y));
    uz.push_back(float(u.z));
    h.push_back(float(len));
    material.push_back(mat);
    return std::nullopt;
  }

  // The box of the two cap discs: the span of both centres grown by r·sqrt(1 − u_k²) per
  // axis (docs/hard-cases.md C7), computed in double and rounded outward.
  Bounds3f bounds(uint32_t i) const {
    glm::dvec3 b(base(i)), top = glm::dvec3(base(i)) + glm::dvec3(axis(i));
    glm::dvec3 u = normalize(glm::dvec3(axis(i)));
    double rad = r[i];
    glm::dvec3 g(rad * std::sqrt(std::max(0.0, 1 - u.x * u.x)),
                 rad * std::sqrt(std::max(0.0, 1 - u.y * u.y)),
                 rad * std::sqrt(std::max(0.0, 1 - u.z * u.z)));
    Bounds3d bb(b, top);
    return round_out(Bounds3d(bb.lo - g, bb.hi + g));
  }
};

struct Cylinder {
  using Table = CylinderTable;
  static constexpr std::string_view name = "cylinder", plural = "cylinders", keyword = "cylinder";
  static constexpr int param_count = 7;
  static constexpr bool two_sided = false;
  static constexpr double sah_test_cost = 1.0;
  // The SIMD tracer computes its hits' surfaces in double lanes for hit records and in float
  // lanes, with their bound, for the render's columns (cylinder_packet.h).
  static constexpr bool surface_in_lanes = true;
  static constexpr bool surface_in_float_lanes = true;
  // Few of a render's batches hold a cylinder: the float surfaces' pass computes them out of its
  // loop (src/trace/float_surfaces_impl.h, rare_float_surfaces).
  static constexpr bool float_surface_out_of_line = true;
  static double area(const Table& t, uint32_t i);
  // A uniform point on the surface and its outward normal; u_part picks the part (a box's
  // face, a cylinder's side or cap) in proportion to its area.
  static AreaSample sample_area(const Table& t, uint32_t i, double u_part, double u1, double u2);
  // A cylinder emits from its outside only, and a point sees at most one cap and, of the side,
  // only points within the half about the direction from the axis toward it (prims/
  // cylinder_light.h). Light sampling draws from that cap and that half alone, by area, and
  // area_seen_from is the density's denominator, for the sample and for MIS alike. 0 where
  // nothing faces the point (inside, or within the radius between the caps' planes).
  static double area_seen_from(const Table& t, uint32_t i, const glm::dvec3& ref);
  // A uniform point on the parts that face `ref`, u_part picking the part in proportion to its
  // area, and its outward normal; a zero normal where none does.
  static AreaSample sample_area_seen_from(const Table& t, uint32_t i, const glm::dvec3& ref,
                                          double u_part, double u1, double u2);
};

namespace detail {
// The interval of the ray inside a capped cylinder, in double: the infinite cylinder's
// quadratic in the components perpendicular to the unit axis (Hearn–Baker discriminant, as for
// spheres: docs/hard-cases.md C5) intersected with the axial slab 0 ≤ (p − b)·u ≤ h. Rays parallel
// to the axis and rays perpendicular to it are handled by their own branches, so no 0·inf
// appears (C1, C4). Returns false when the line misses.
inline bool cylinder_interval(const CylinderTable& c, uint32_t i, const Rayd& ray, double& t0,
                              double& t1) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  glm::dvec3 u = normalize(glm::dvec3(c.axis(i)));
  double h = length(glm::dvec3(c.axis(i))), r = c.r[i];
  glm::dvec3 f = ray.o - glm::dvec3(c.base(i));
  double fa = dot(f, u), da = dot(ray.d, u);
  glm::dvec3 fp = f - fa * u, dp = ray.d - da * u;
  double a = dot(dp, dp), b = dot(fp, dp);
  double s0 = -kInf, s1 = kInf;
  if (a == 0) {
    if (!(dot(fp, fp) <= r * r)) return false;  // parallel, outside
  } else {
    glm::dvec3 l = fp - (b / a) * dp;
    double disc = r * r - dot(l, l);
    if (!(disc >= 0)) return false;
    solve_quadratic(a, b, dot(fp, fp) - r * r, a * disc, s0, s1);
  }
  double z0 = -kInf, z1 = kInf;
  if (da == 0) {
    if (!(fa >= 0 && fa <= h)) return false;  // perpendicular, outside the slab
  } else {
    double ta = -fa / da, tb = (h - fa) / da;
    z0 = std::min(ta, tb);
    z1 = std::max(ta, tb);
  }
  t0 = std::max(s0, z0);
  t1 = std::min(s1, z1);
  return t0 <= t1;  // inclusive: a ray through the rim hits (C3)
}
}  // namespace detail

inline double intersect_ref(const CylinderTable& c, uint32_t i, const Rayd& ray) {
  double t0, t1;
  if (!detail::cylinder_interval(c, i, ray, t0, t1)) return std::numeric_limits<double>::infinity();
  return first_in_range(t0, t1, ray);
}

// The surface at a hit, written once over the number type N (core/numbers.h) and its 3-vector
// V3: double for surface_ref, double lanes for the SIMD tracer's hit records, float lanes for the
// render's float columns (cylinder_packet.h), given the base b, the unit axis u, the height h
// and the radius r. The part hit is the one the point o + t·d is nearest to, a cap (±u) or the
// side (radial), and the point is projected onto that part (pbrt-v4 Cylinder::Intersect
// reprojects onto the side; Pharr, Jakob, Humphreys, 4th ed., §6.8.5), so that its error no
// longer grows with the distance the ray travelled: on the side, b + u·z + n·r, with z the
// point's coordinate along the axis and n its direction from the axis; on a cap, b + u·c +
// (its offset from the axis), with c = 0 or h. `spread`, `rlen`, `on_axis` and `offset` are the
// parts cylinder_point_bound weighs.
template <class N, class V3>
struct CylinderSurface {
  using Mask = decltype(N() < N());
  V3 p, n;
  V3 on_axis, offset;  // p = on_axis + offset, on_axis = b + u·(z or c)
  N axial;             // z or c
  N spread, rlen;      // |q|₁ + |z| with q = o + t·d − b, and the distance from the axis
  N inv_rlen;          // 1/rlen: one division for the normal's three components and the bound
  Mask cap;
};
template <class N, class V3>
[[gnu::always_inline]] inline CylinderSurface<N, V3> cylinder_surface(const V3& b, const V3& u,
                                                                      const N& h, const N& r,
                                                                      const V3& o, const V3& d,
                                                                      const N& t) {
  using K = Num<N>;
  CylinderSurface<N, V3> s;
  const V3 q{o.x + d.x * t - b.x, o.y + d.y * t - b.y, o.z + d.z * t - b.z};
  const N z = q.x * u.x + q.y * u.y + q.z * u.z;  // glm::dot's order
  const V3 radial{q.x - z * u.x, q.y - z * u.y, q.z - z * u.z};
  s.rlen = K::sqrt(radial.x * radial.x + radial.y * radial.y + radial.z * radial.z);
  const N below = K::abs(z), above = K::abs(z - h);
  const N cap_dist = K::select(above < below, above, below);  // std::min's choice
  s.cap = (cap_dist < K::abs(s.rlen - r)) | !(s.rlen > N(0.0));
  const auto lower = z < h / N(2.0);
  // K::negate, not unary minus: an axis component of +0 turns to −0 (the shading frame reads
  // n.z's sign), as the scalar's -u does and AVX-512's 0 − x would not.
  auto axis_normal = [&](const N& uk) { return K::select(lower, K::negate(uk), uk); };
  s.inv_rlen = N(1.0) / s.rlen;
  const V3 side{radial.x * s.inv_rlen, radial.y * s.inv_rlen, radial.z * s.inv_rlen};
  s.n = V3{K::select(s.cap, axis_normal(u.x), side.x), K::select(s.cap, axis_normal(u.y), side.y),
           K::select(s.cap, axis_normal(u.z), side.z)};
  // The part's own extent: o + t·d may lie past the rim (its error grows with the distance the
  // ray travelled), so the side's z is kept within [0, h] and a cap's offset within r; the point
  // then lies on the finite cylinder, not on the side's or the cap's plane beyond it.
  s.axial = K::select(s.cap, K::select(lower, N(0.0), h), K::min(K::max(z, N(0.0)), h));
  const N inside = K::min(r * s.inv_rlen, N(1.0));  // a cap's offset scaled back to the rim
  s.offset = V3{K::select(s.cap, radial.x * inside, side.x * r),
                K::select(s.cap, radial.y * inside, side.y * r),
                K::select(s.cap, radial.z * inside, side.z * r)};
  s.on_axis = V3{b.x + u.x * s.axial, b.y + u.y * s.axial, b.z + u.z * s.axial};
  s.p = V3{s.on_axis.x + s.offset.x, s.on_axis.y + s.offset.y, s.on_axis.z + s.offset.z};
  s.spread = K::abs(q.x) + K::abs(q.y) + K::abs(q.z) + K::abs(z);
  return s;
}

// A bound on the error of cylinder_surface's point computed in float, for the offset along its
// normal: dot(|n|, bound) bounds the point's distance from the cylinder of the reference (base b,
// axis u·h in double, which is parallel to the float u: only u's length differs from 1, by at
// most two roundoffs). Derived in the manner of pbrt-v4 §6.8 (Pharr, Jakob, Humphreys, 4th ed.):
// - The point's offset from the axis, radial = q − u·z, keeps a part along the axis made of
//   roundoffs: z's dot product (γ3 of |q|₁), u's length (γ2 of |q|), radial's own product and
//   difference (γ2 of |q|₁ + |z|); γ8 of spread = |q|₁ + |z| covers them.
// - On a cap, that part is the point's distance from the cap's plane (b + u·c lies on it: the
//   reference's height is |u·h| = |u|·h): D = γ8·spread.
// - On the side, b + u·z lies on the axis, and b + u·z + n·r is |n⊥|·r from it, where n⊥ is n's
//   part across the axis: |n| is within γ6 of 1 (the square root, the reciprocal, the products) and
//   n is tilted out of the plane across the axis by the radial's part along it, sin θ ≤ γ8·spread /
//   rlen, which shortens n⊥ by at most sin²θ: D = r·(γ6 + min(sin²θ, 1)).
// D goes into each component as |n_k|·D (whose projection on the normal is |n|²·D, kept at or
// above D by γ6 more), plus one roundoff of each sum and product that forms the point: u·(z or c),
// b + u·(z or c), n·r and the final sum. Every term carries 2^-20 more for the bound's own float
// roundings.
template <class N, class V3>
V3 cylinder_point_bound(const CylinderSurface<N, V3>& s, const V3& u, const N& r) {
  using K = Num<N>;
  const N slack(1 + 0x1p-20), axial_part(gamma_float(8)), unit(gamma_float(6));
  const N sin_theta = axial_part * s.spread * s.inv_rlen;
  const N side = r * (unit + K::min(sin_theta * sin_theta, N(1.0)));
  const N own(kFloatUnitRoundoff * (1 + 0x1p-20));
  auto rounding = [&](const N& uk, const N& on_axis_k, const N& offset_k, const N& pk) {
    return (K::abs(uk * s.axial) + K::abs(on_axis_k) + K::abs(offset_k) + K::abs(pk)) * own;
  };
  const V3 e{rounding(u.x, s.on_axis.x, s.offset.x, s.p.x),
             rounding(u.y, s.on_axis.y, s.offset.y, s.p.y),
             rounding(u.z, s.on_axis.z, s.offset.z, s.p.z)};
  // A displacement e of a point r from the axis moves it off the side by at most e·n plus
  // |e|²/2r across it (the chord's sagitta), which counts where the cylinder is only a few
  // roundoffs of its coordinates wide; a cap is flat.
  const N across = (e.x * e.x + e.y * e.y + e.z * e.z) / (N(2.0) * r);
  const N distance =
      K::select(s.cap, axial_part * s.spread, side + across) * N(1 + gamma_float(6)) * slack;
  return V3{K::abs(s.n.x) * distance + e.x, K::abs(s.n.y) * distance + e.y,
            K::abs(s.n.z) * distance + e.z};
}

inline Surface surface_ref(const CylinderTable& c, uint32_t i, const Rayd& ray, double t) {
  const glm::dvec3 axis(c.axis(i));
  const double h = length(axis);
  const CylinderSurface<double, glm::dvec3> s = cylinder_surface<double>(
      glm::dvec3(c.base(i)), normalize(axis), h, double(c.r[i]), ray.o, ray.d, t);
  return {s.p, s.n, s.n};
}

// The side: u = the angle around the axis / 2π, from the axis's Frame (core/warps.h, Duff et
// al. 2017: it depends on the axis alone) s towards t; v = 0 at the base to 1 at the top.
// The caps: u, v = 0.5 + (the point's s and t coordinates from the cap's centre) / 2r.
inline TexCoord texcoord_ref(const CylinderTable& c, uint32_t i, const Surface& s) {
  glm::dvec3 axis(c.axis(i));
  double h = length(axis);
  Frame f(axis / h);
  glm::dvec3 local = f.to_local(s.p - glm::dvec3(c.base(i)));
  if (std::abs(dot(s.ng, f.n)) > 0.5) {  // a cap: its normal is ±axis
    double two_r = 2.0 * c.r[i];
    return {0.5 + local.x / two_r, 0.5 + local.y / two_r};
  }
  double phi = std::atan2(local.y, local.x);
  if (phi < 0) phi += 2 * kPi;
  double u = phi / (2 * kPi);
  return {u < 1 ? u : 0.0, std::clamp(local.z / h, 0.0, 1.0)};
}

}  // namespace raylane
