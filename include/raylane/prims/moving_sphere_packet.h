// Moving spheres: the SIMD kernel (moving_sphere.h has the table and the reference). Lane code:
// included only through prims/prim_packets.h by the SIMD tracer's per-ISA translation units.
#pragma once

#include "raylane/prims/prim_list.h"
#include "raylane/prims/sphere_packet.h"
#include "raylane/simd/packet.h"

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

}  // namespace raylane
