// A CSG leaf's interval on each lane's ray, by the float operations of its own kind's kernel
// (sphere_packet.h, box_packet.h, cylinder_packet.h), so that a leaf's ends are the t its kind
// alone would commit and carry that kernel's error bound. Lane code (csg_packet.h).
#pragma once

#include <limits>

#include "raylane/prims/csg.h"
#include "raylane/simd/packet.h"

namespace raylane::detail {

// Keeps [tn, tf] where `ok` and tn ≤ tf, and makes the interval empty, (+inf, +inf), elsewhere:
// a NaN end never leaves a leaf kernel.
template <class A>
inline void csg_keep_interval(const simd::Mask<A>& ok, const simd::Floats<A>& tn,
                              const simd::Floats<A>& tf, simd::Floats<A>& t0, simd::Floats<A>& t1) {
  const simd::Floats<A> inf(std::numeric_limits<float>::infinity());
  simd::Mask<A> keep = ok & (tn <= tf);
  t0 = simd::select<A>(keep, tn, inf);
  t1 = simd::select<A>(keep, tf, inf);
}

// The Hearn–Baker discriminant and the Press roots (sphere_row_lanes).
template <class A>
inline void csg_sphere_lanes(const SphereTable& s, uint32_t i, const RayPacket<A>& r,
                             simd::Floats<A>& t0, simd::Floats<A>& t1) {
  using F = simd::Floats<A>;
  const F dd = r.dx * r.dx + r.dy * r.dy + r.dz * r.dz;
  F fx = r.ox - F(s.cx[i]), fy = r.oy - F(s.cy[i]), fz = r.oz - F(s.cz[i]);
  F b = fx * r.dx + fy * r.dy + fz * r.dz;
  F k = b / dd;
  F lx = fx - k * r.dx, ly = fy - k * r.dy, lz = fz - k * r.dz;
  F radius(s.r[i]);
  F rr = radius * radius;
  F disc = rr - (lx * lx + ly * ly + lz * lz);
  F sq = xsimd::sqrt(dd * disc);
  F q = -(b + simd::select<A>(b < F(0.0f), -sq, sq));
  F c = fx * fx + fy * fy + fz * fz - rr;
  F r0 = c / q, r1 = q / dd;
  csg_keep_interval<A>(disc >= F(0.0f), simd::select<A>(r0 < r1, r0, r1),
                       simd::select<A>(r0 < r1, r1, r0), t0, t1);
}

// Slabs with NaN-keeping extrema, near and far by the sign of 1/d (box_packet.h).
template <class A>
inline void csg_box_lanes(const BoxTable& b, uint32_t i, const RayPacket<A>& r, simd::Floats<A>& t0,
                          simd::Floats<A>& t1) {
  using F = simd::Floats<A>;
  const F inf(std::numeric_limits<float>::infinity());
  F tn = -inf, tf = inf;
  auto slab = [&](float lo, float hi, const F& o, const F& inv) {
    F tlo = (F(lo) - o) * inv, thi = (F(hi) - o) * inv;
    auto neg = inv < F(0.0f);
    tn = simd::max_keep<A>(simd::select<A>(neg, thi, tlo), tn);
    tf = simd::min_keep<A>(simd::select<A>(neg, tlo, thi), tf);
  };
  slab(b.lox[i], b.hix[i], r.ox, r.inv_dx);
  slab(b.loy[i], b.hiy[i], r.oy, r.inv_dy);
  slab(b.loz[i], b.hiz[i], r.oz, r.inv_dz);
  csg_keep_interval<A>(tn <= tf, tn, tf, t0, t1);
}

// The side's quadratic perpendicular to the axis and the axial slab (cylinder_packet.h).
template <class A>
inline void csg_cylinder_lanes(const CylinderTable& c, uint32_t i, const RayPacket<A>& r,
                               simd::Floats<A>& t0, simd::Floats<A>& t1) {
  using F = simd::Floats<A>;
  const F inf(std::numeric_limits<float>::infinity()), zero(0.0f);
  F ux(c.ux[i]), uy(c.uy[i]), uz(c.uz[i]);
  F fx = r.ox - F(c.bx[i]), fy = r.oy - F(c.by[i]), fz = r.oz - F(c.bz[i]);
  F fa = fx * ux + fy * uy + fz * uz, da = r.dx * ux + r.dy * uy + r.dz * uz;
  F px = fx - fa * ux, py = fy - fa * uy, pz = fz - fa * uz;
  F qx = r.dx - da * ux, qy = r.dy - da * uy, qz = r.dz - da * uz;
  F a = qx * qx + qy * qy + qz * qz;
  F b = px * qx + py * qy + pz * qz;
  F radius(c.r[i]);
  F rr = radius * radius;
  F pp = px * px + py * py + pz * pz;
  F k = b / a;
  F lx = px - k * qx, ly = py - k * qy, lz = pz - k * qz;
  F disc = rr - (lx * lx + ly * ly + lz * lz);
  auto parallel = a == zero;
  auto side_ok = (parallel & (pp <= rr)) | ((!parallel) & (disc >= zero));
  F sq = xsimd::sqrt(a * disc);
  F q = -(b + simd::select<A>(b < zero, -sq, sq));
  F s0 = (pp - rr) / q, s1 = q / a;
  F side_n = simd::select<A>(parallel, -inf, simd::select<A>(s0 < s1, s0, s1));
  F side_f = simd::select<A>(parallel, inf, simd::select<A>(s0 < s1, s1, s0));
  F inv = F(1.0f) / da;
  F ta = (zero - fa) * inv, tb = (F(c.h[i]) - fa) * inv;
  F tn = simd::max_keep<A>(side_n, simd::max_keep<A>(simd::select<A>(inv < zero, tb, ta), -inf));
  F tf = simd::min_keep<A>(side_f, simd::min_keep<A>(simd::select<A>(inv < zero, ta, tb), inf));
  csg_keep_interval<A>(side_ok, tn, tf, t0, t1);
}

template <class A>
inline void csg_leaf_interval_lanes(const CsgTable& c, uint32_t leaf, const RayPacket<A>& r,
                                    simd::Floats<A>& t0, simd::Floats<A>& t1) {
  const uint32_t row = c.leaf_row[leaf];
  switch (c.leaf_kind[leaf]) {
    case kCsgSphere:
      return csg_sphere_lanes<A>(c.spheres, row, r, t0, t1);
    case kCsgBox:
      return csg_box_lanes<A>(c.boxes, row, r, t0, t1);
    default:
      return csg_cylinder_lanes<A>(c.cylinders, row, r, t0, t1);
  }
}

}  // namespace raylane::detail
