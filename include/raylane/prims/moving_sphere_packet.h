// Moving spheres: the SIMD kernel (moving_sphere.h has the table and the reference). Lane code:
// included only through prims/prim_packets.h by the SIMD tracer's per-ISA translation units.
#pragma once

#include "raylane/prims/prim_list.h"
#include "raylane/prims/sphere_packet.h"
#include "raylane/simd/packet.h"
#include "raylane/simd/surface_lanes.h"

namespace raylane {

// The packet kernel, in float, with rays or rows in the lanes (`Rows`, simd/packet.h): each
// lane's ray meets the row's sphere where its centre is at that lane's time, c0 + t·m (the
// reference's centre, moving_sphere.h), and then the sphere's kernel (sphere_packet.h).
template <class A, class Rows>
[[gnu::always_inline]] inline void intersect_packet(const MovingSphereTable& s, Rows rows,
                                                    const RayPacket<A>& r, HitPacket<A>& h) {
  using F = simd::Floats<A>;
  const F dd = r.dx * r.dx + r.dy * r.dy + r.dz * r.dz;
  for (; rows.more(); rows.next()) {
    F cx = rows.col(s.cx) + r.time * rows.col(s.mx);
    F cy = rows.col(s.cy) + r.time * rows.col(s.my);
    F cz = rows.col(s.cz) + r.time * rows.col(s.mz);
    sphere_row_lanes<A>(r.ox - cx, r.oy - cy, r.oz - cz, rows.col(s.r), dd, rows.mask(),
                        rows.bits(tag_of<MovingSphere>), r, h);
  }
}

// sphere_surface (sphere.h) for one hit per float lane about the centre at the ray's time, as
// the kernel above computes it, with its bound (moving_sphere_point_bound). The surfaces' pass
// calls it out of its loop (MovingSphere::float_surface_out_of_line).
template <class A>
[[gnu::always_inline]] inline FloatSurfaceLanes<A> surface_float_lanes(
    const MovingSphereTable& s, const simd::Ints<A>& rows, const FloatHitRayLanes<A>& r) {
  using F = simd::Floats<A>;
  const F time = r.time();
  const simd::FloatVec3<A> m = read_rows3<A>(s.mx, s.my, s.mz, rows);
  const simd::FloatVec3<A> c = moving_center<F>(read_rows3<A>(s.cx, s.cy, s.cz, rows), m, time);
  const F radius = read_rows<A>(s.r, rows);
  const SphereSurface<simd::FloatVec3<A>> x = sphere_surface<F>(c, radius, r.o, r.d, r.t);
  return surface_lanes_of<A>(x.p, x.n, x.n, moving_sphere_point_bound<F>(x, c, m, time, radius));
}

}  // namespace raylane
