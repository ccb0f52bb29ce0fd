// Mesh triangles: the SIMD kernel (triangle.h has the table and the reference). Lane code: included
// only through prims/prim_packets.h by the SIMD tracer's per-ISA translation units.
#pragma once

#include "raylane/prims/prim_list.h"
#include "raylane/simd/packet.h"
#include "raylane/simd/surface_lanes.h"

namespace raylane {

// The vertices of the current rows relative to the ray origin, permuted and sheared by the
// ray's frame (RayShear, computed once per ray), in one of two ways with the same roundings,
// so both give the same answers:
// - LaneShear: every lane may have its own permutation, so each coordinate is selected per
//   lane;
// - ColumnShear: every active lane has the same permutation (a single ray, or a coherent
//   packet), so the permuted columns are loaded directly.
inline std::array<const std::vector<float>*, 3> vertex_columns(const TriangleTable& tri, int v) {
  if (v == 0) return {&tri.p0x, &tri.p0y, &tri.p0z};
  if (v == 1) return {&tri.p1x, &tri.p1y, &tri.p1z};
  return {&tri.p2x, &tri.p2y, &tri.p2z};
}

template <class A>
struct LaneShear {
  using F = simd::Floats<A>;
  const RayPacket<A>& r;

  template <class Rows>
  void vertex(const TriangleTable& tri, const Rows& rows, int v, F& x, F& y, F& z) const {
    const RayShear<A>& s = r.shear;
    const auto& c = vertex_columns(tri, v);
    F ax = rows.col(*c[0]) - r.ox, ay = rows.col(*c[1]) - r.oy, az = rows.col(*c[2]) - r.oz;
    F kz = RayShear<A>::pick(s.z_is, ax, ay, az);
    x = simd::fma<A>(-s.sx, kz, RayShear<A>::pick(s.x_is, ax, ay, az));
    y = simd::fma<A>(-s.sy, kz, RayShear<A>::pick(s.y_is, ax, ay, az));
    z = s.sz * kz;
  }
};

template <class A>
struct ColumnShear {
  using F = simd::Floats<A>;
  std::array<const std::vector<float>*, 3> col[3];  // [vertex][sheared axis x, y, z]
  F ox, oy, oz, sx, sy, sz;                         // origin in sheared axis order

  ColumnShear(const TriangleTable& tri, const RayPacket<A>& r)
      : sx(r.shear.sx), sy(r.shear.sy), sz(r.shear.sz) {
    const RayShear<A>& s = r.shear;
    for (int v = 0; v < 3; ++v) {
      auto c = vertex_columns(tri, v);
      col[v] = {c[s.kx], c[s.ky], c[s.kz]};
    }
    const F* o[3] = {&r.ox, &r.oy, &r.oz};
    ox = *o[s.kx], oy = *o[s.ky], oz = *o[s.kz];
  }

  template <class Rows>
  void vertex(const TriangleTable&, const Rows& rows, int v, F& x, F& y, F& z) const {
    F az = rows.col(*col[v][2]) - oz;
    x = simd::fma<A>(-sx, az, rows.col(*col[v][0]) - ox);
    y = simd::fma<A>(-sy, az, rows.col(*col[v][1]) - oy);
    z = sz * az;
  }
};

// a·b − c·d with the exact sign in every lane (Kahan; see difference_of_products): the
// shared edge of two triangles gets opposite signs from both, so nothing leaks between them
// (docs/hard-cases.md T2).
template <class A>
inline simd::Floats<A> difference_of_products_lanes(const simd::Floats<A>& a,
                                                    const simd::Floats<A>& b,
                                                    const simd::Floats<A>& c,
                                                    const simd::Floats<A>& d) {
  simd::Floats<A> cd = c * d;
  simd::Floats<A> err = simd::fma<A>(-c, d, cd);
  return simd::fma<A>(a, b, -cd) + err;
}

// Whether some of the edge functions u, v, w are below 0 and some above, which rejects the
// lane (Woop et al. 2013, §3: a hit needs all ≥ 0 or all ≤ 0): the smallest below 0 and the
// largest above. Two compares on a min and a max, where six compares joined by four mask ORs
// had AVX-512 code move every mask through a general register, a chain in every row (1.31M
// mesh shadow rays: 10 % of the leaf's samples on the last mask move). Contract: the same
// answer as the six compares wherever u, v and w are numbers (min and max are exact, and
// −0 < 0 is false either way); where one is NaN the answer is unspecified, and unneeded: det
// and t are NaN too, so t > tmin rejects the lane.
template <class A>
inline simd::Mask<A> mixed_signs(const simd::Floats<A>& u, const simd::Floats<A>& v,
                                 const simd::Floats<A>& w) {
  const simd::Floats<A> zero(0.0f);
  simd::Floats<A> lowest = xsimd::min(xsimd::min(u, v), w);
  simd::Floats<A> highest = xsimd::max(xsimd::max(u, v), w);
  return (lowest < zero) & (highest > zero);
}

// The watertight test in float, per lane (Woop et al. 2013): vertices relative to the
// origin, permuted and sheared; edge functions U, V, W with their exact sign; accept all ≥ 0
// or all ≤ 0 with det ≠ 0; t = T/det.
template <class A, class Rows, class Shear>
[[gnu::always_inline]] inline void watertight_rows(const TriangleTable& tri, Rows rows,
                                                   const Shear& shear, const RayPacket<A>& r,
                                                   HitPacket<A>& h) {
  using F = simd::Floats<A>;
  const F zero(0.0f);
  for (; rows.more(); rows.next()) {
    F ax, ay, az, bx, by, bz, cx, cy, cz;
    shear.vertex(tri, rows, 0, ax, ay, az);
    shear.vertex(tri, rows, 1, bx, by, bz);
    shear.vertex(tri, rows, 2, cx, cy, cz);
    F u = difference_of_products_lanes<A>(cx, by, cy, bx);
    F v = difference_of_products_lanes<A>(ax, cy, ay, cx);
    F e = difference_of_products_lanes<A>(bx, ay, by, ax);
    F det = u + v + e;
    simd::Mask<A> hit = rows.mask() & (det != zero) & !mixed_signs<A>(u, v, e);
    if (simd::none<A>(hit)) continue;
    F t = (u * az + v * bz + e * cz) / det;
    commit_hit<A>(t, hit & (t > r.tmin) & (t < h.t), rows.bits(tag_of<Triangle>), h);
  }
}

// The packet kernel: permuted columns when the lanes share the ray's axes, selects otherwise.
template <class A, class Rows>
[[gnu::always_inline]] inline void intersect_packet(const TriangleTable& tri, Rows rows,
                                                    const RayPacket<A>& r, HitPacket<A>& h) {
  if constexpr (!Rows::kOneRay) {
    if (!r.shear.uniform) return watertight_rows<A>(tri, rows, LaneShear<A>{r}, r, h);
  }
  watertight_rows<A>(tri, rows, ColumnShear<A>(tri, r), r, h);
}

// triangle_surface (triangle.h) for one hit per float lane, with its bound
// (triangle_point_bound).
template <class A>
[[gnu::always_inline]] inline FloatSurfaceLanes<A> surface_float_lanes(
    const TriangleTable& tri, const simd::Ints<A>& rows, const FloatHitRayLanes<A>& r) {
  using V3 = simd::FloatVec3<A>;
  const std::array<V3, 3> v{read_rows3<A>(tri.p0x, tri.p0y, tri.p0z, rows),
                            read_rows3<A>(tri.p1x, tri.p1y, tri.p1z, rows),
                            read_rows3<A>(tri.p2x, tri.p2y, tri.p2z, rows)};
  const std::array<V3, 3> vn{read_rows3<A>(tri.n0x, tri.n0y, tri.n0z, rows),
                             read_rows3<A>(tri.n1x, tri.n1y, tri.n1z, rows),
                             read_rows3<A>(tri.n2x, tri.n2y, tri.n2z, rows)};
  const TriangleSurface<V3> s = triangle_surface<simd::Floats<A>>(v, vn, r.o, r.d, r.t);
  return surface_lanes_of<A>(s.p, s.ng, s.ns,
                             triangle_point_bound<simd::Floats<A>>(s, v, r.o, r.d, r.t));
}

}  // namespace raylane
