// Capped cylinders: the SIMD kernel (cylinder.h has the table and the reference). Lane code:
// included only through prims/prim_packets.h by the SIMD tracer's per-ISA translation units.
#pragma once

#include "raylane/prims/prim_list.h"
#include "raylane/simd/packet.h"
#include "raylane/simd/surface_lanes.h"

namespace raylane {

// The packet kernel, in float: the side interval from the quadratic in the components
// perpendicular to the unit axis (Hearn–Baker discriminant, Press roots, as for spheres),
// intersected with the axial slab [0, h] (docs/hard-cases.md §3). A ray parallel to the axis
// (|d⊥|² = 0) has the whole line inside the side when |f⊥| ≤ r; a ray perpendicular to the
// axis has the whole line inside the slab when 0 ≤ f·u ≤ h (NaN-keeping extrema).
template <class A, class Rows>
[[gnu::always_inline]] inline void intersect_packet(const CylinderTable& c, Rows rows,
                                                    const RayPacket<A>& r, HitPacket<A>& h) {
  using F = simd::Floats<A>;
  const F inf(std::numeric_limits<float>::infinity()), zero(0.0f);
  for (; rows.more(); rows.next()) {
    F ux = rows.col(c.ux), uy = rows.col(c.uy), uz = rows.col(c.uz);
    F fx = r.ox - rows.col(c.bx), fy = r.oy - rows.col(c.by), fz = r.oz - rows.col(c.bz);
    F fa = fx * ux + fy * uy + fz * uz, da = r.dx * ux + r.dy * uy + r.dz * uz;
    F px = fx - fa * ux, py = fy - fa * uy, pz = fz - fa * uz;        // f⊥
    F qx = r.dx - da * ux, qy = r.dy - da * uy, qz = r.dz - da * uz;  // d⊥
    F a = qx * qx + qy * qy + qz * qz;
    F b = px * qx + py * qy + pz * qz;
    F radius = rows.col(c.r), rr = radius * radius;
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
    F ta = (zero - fa) * inv, tb = (rows.col(c.h) - fa) * inv;
    F t0 = simd::max_keep<A>(side_n, simd::max_keep<A>(simd::select<A>(inv < zero, tb, ta), -inf));
    F t1 = simd::min_keep<A>(side_f, simd::min_keep<A>(simd::select<A>(inv < zero, ta, tb), inf));
    commit_solid_hit<A>(t0, t1, r, rows.mask() & side_ok & (t0 <= t1), rows.bits(tag_of<Cylinder>),
                        h);
  }
}

// cylinder_surface (cylinder.h) for one hit per double lane: surface_ref's answers bit for bit.
// The axis u·h is exact in double (cylinder.h); its length and direction are taken as the
// reference takes them.
template <class A>
SurfaceLanes<A> surface_lanes(const CylinderTable& c, const uint32_t* rows,
                              const HitRayLanes<A>& r) {
  using D = simd::Doubles<A>;
  const simd::DoubleVec3<A> uf = load_rows3<A>(c.ux, c.uy, c.uz, rows);
  const D hf = simd::load_rows<A>(c.h, rows);
  const simd::DoubleVec3<A> a{uf.x * hf, uf.y * hf, uf.z * hf};
  const D h = simd::sqrt<A>(dot_lanes<A>(a, a));
  const simd::DoubleVec3<A> u{a.x / h, a.y / h, a.z / h};
  const CylinderSurface<D, simd::DoubleVec3<A>> s = cylinder_surface<D>(
      load_rows3<A>(c.bx, c.by, c.bz, rows), u, h, D(simd::load_rows<A>(c.r, rows)), r.o, r.d, r.t);
  return {s.p, s.n};
}

// cylinder_surface for one hit per float lane, on the table's float unit axis and height, with
// its bound (cylinder_point_bound). The surfaces' pass calls it out of its loop
// (Cylinder::float_surface_out_of_line).
template <class A>
[[gnu::always_inline]] inline FloatSurfaceLanes<A> surface_float_lanes(
    const CylinderTable& c, const simd::Ints<A>& rows, const FloatHitRayLanes<A>& r) {
  using F = simd::Floats<A>;
  const simd::FloatVec3<A> u = read_rows3<A>(c.ux, c.uy, c.uz, rows);
  const F radius = read_rows<A>(c.r, rows);
  const CylinderSurface<F, simd::FloatVec3<A>> s = cylinder_surface<F>(
      read_rows3<A>(c.bx, c.by, c.bz, rows), u, read_rows<A>(c.h, rows), radius, r.o, r.d, r.t);
  return surface_lanes_of<A>(s.p, s.n, s.n, cylinder_point_bound<F>(s, u, radius));
}

}  // namespace raylane
