// Spheres: the SIMD kernel (sphere.h has the table and the reference). Lane code: included
// only through prims/prim_packets.h by the SIMD tracer's per-ISA translation units.
#pragma once

#include "raylane/prims/prim_list.h"
#include "raylane/simd/packet.h"
#include "raylane/simd/surface_lanes.h"

namespace raylane {

// One row of spheres against the packet, given f = o − c per lane (c the centre the row has for
// that lane's ray) and d·d: the discriminant in the Hearn–Baker form r² − |f − (f·d/d·d)·d|² and
// the roots by the Press form, as in the reference (Haines et al. 2019, Ray Tracing Gems ch. 7).
// Updates h where a lane of `rows_mask` finds a nearer hit.
template <class A>
[[gnu::always_inline]] inline void sphere_row_lanes(
    const simd::Floats<A>& fx, const simd::Floats<A>& fy, const simd::Floats<A>& fz,
    const simd::Floats<A>& radius, const simd::Floats<A>& dd, const simd::Mask<A>& rows_mask,
    const simd::Ints<A>& bits, const RayPacket<A>& r, HitPacket<A>& h) {
  using F = simd::Floats<A>;
  F b = fx * r.dx + fy * r.dy + fz * r.dz;
  F k = b / dd;
  F lx = fx - k * r.dx, ly = fy - k * r.dy, lz = fz - k * r.dz;
  F rr = radius * radius;
  F disc = rr - (lx * lx + ly * ly + lz * lz);
  simd::Mask<A> hit = rows_mask & (disc >= F(0.0f));
  if (simd::none<A>(hit)) return;
  F sq = xsimd::sqrt(dd * disc);
  F q = -(b + simd::select<A>(b < F(0.0f), -sq, sq));
  F c = fx * fx + fy * fy + fz * fz - rr;
  F t0 = c / q, t1 = q / dd;
  F tn = simd::select<A>(t0 < t1, t0, t1), tf = simd::select<A>(t0 < t1, t1, t0);
  commit_solid_hit<A>(tn, tf, r, hit, bits, h);
}

// The packet kernel, in float, with rays or rows in the lanes (`Rows`, simd/packet.h).
template <class A, class Rows>
[[gnu::always_inline]] inline void intersect_packet(const SphereTable& s, Rows rows,
                                                    const RayPacket<A>& r, HitPacket<A>& h) {
  using F = simd::Floats<A>;
  const F dd = r.dx * r.dx + r.dy * r.dy + r.dz * r.dz;
  for (; rows.more(); rows.next()) {
    F fx = r.ox - rows.col(s.cx), fy = r.oy - rows.col(s.cy), fz = r.oz - rows.col(s.cz);
    sphere_row_lanes<A>(fx, fy, fz, rows.col(s.r), dd, rows.mask(), rows.bits(tag_of<Sphere>), r,
                        h);
  }
}

// sphere_surface (sphere.h) for one hit per double lane: surface_ref's answers bit for bit.
template <class A>
SurfaceLanes<A> surface_lanes(const SphereTable& s, const uint32_t* rows, const HitRayLanes<A>& r) {
  const simd::DoubleVec3<A> c = load_rows3<A>(s.cx, s.cy, s.cz, rows);
  const SphereSurface<simd::DoubleVec3<A>> x =
      sphere_surface<simd::Doubles<A>>(c, simd::load_rows<A>(s.r, rows), r.o, r.d, r.t);
  return {x.p, x.n};
}

// sphere_surface for one hit per float lane, with its bound (sphere_point_bound).
template <class A>
[[gnu::always_inline]] inline FloatSurfaceLanes<A> surface_float_lanes(
    const SphereTable& s, const simd::Ints<A>& rows, const FloatHitRayLanes<A>& r) {
  const simd::FloatVec3<A> c = read_rows3<A>(s.cx, s.cy, s.cz, rows);
  const SphereSurface<simd::FloatVec3<A>> x =
      sphere_surface<simd::Floats<A>>(c, read_rows<A>(s.r, rows), r.o, r.d, r.t);
  return surface_lanes_of<A>(x.p, x.n, x.n, sphere_point_bound<simd::Floats<A>>(x.p, x.offset));
}

}  // namespace raylane
