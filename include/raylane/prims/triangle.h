// Mesh triangles (made by the `mesh` command). The table, its reference kernel and its
// packet kernel.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <cmath>
#include <utility>
#include "raylane/core/bounds3.h"
#include "raylane/core/ray.h"

#include "raylane/core/float_util.h"
#include "raylane/prims/prim_ref.h"
#include "raylane/prims/surface.h"
#include "raylane/prims/table_util.h"
#include "raylane/trace/packet.h"

namespace raylane {

// Vertices as given (the watertight test works on vertices relative to the ray origin, so it
// wants p0, p1, p2 rather than edges), and per-vertex shading normals.
struct TriangleTable {
  std::vector<float> p0x, p0y, p0z, p1x, p1y, p1z, p2x, p2y, p2z;
  std::vector<float> n0x, n0y, n0z, n1x, n1y, n1z, n2x, n2y, n2z;
  std::vector<uint32_t> material;

  auto columns() {
    return std::tie(p0x, p0y, p0z, p1x, p1y, p1z, p2x, p2y, p2z, n0x, n0y, n0z, n1x, n1y, n1z, n2x,
                    n2y, n2z, material);
  }
  std::size_t size() const { return p0x.size(); }
  Vec3f p0(uint32_t i) const { return {p0x[i], p0y[i], p0z[i]}; }
  Vec3f p1(uint32_t i) const { return {p1x[i], p1y[i], p1z[i]}; }
  Vec3f p2(uint32_t i) const { return {p2x[i], p2y[i], p2z[i]}; }
  Vec3f n0(uint32_t i) const { return {n0x[i], n0y[i], n0z[i]}; }
  Vec3f n1(uint32_t i) const { return {n1x[i], n1y[i], n1z[i]}; }
  Vec3f n2(uint32_t i) const { return {n2x[i], n2y[i], n2z[i]}; }

  void append(const std::array<Vec3f, 3>& p, const std::array<Vec3f, 3>& n, uint32_t mat) {
    p0x.push_back(p[0].x), p0y.push_back(p[0].y), p0z.push_back(p[0].z);
    p1x.push_back(p[1].x), p1y.push_back(p[1].y), p1z.push_back(p[1].z);
    p2x.push_back(p[2].x), p2y.push_back(p[2].y), p2z.push_back(p[2].z);
    n0x.push_back(n[0].x), n0y.push_back(n[0].y), n0z.push_back(n[0].z);
    n1x.push_back(n[1].x), n1y.push_back(n[1].y), n1z.push_back(n[1].z);
    n2x.push_back(n[2].x), n2y.push_back(n[2].y), n2z.push_back(n[2].z);
    material.push_back(mat);
  }

  // Vertices are exact floats: their min and max need no rounding.
  Bounds3f bounds(uint32_t i) const {
    Bounds3f b;
    b.extend(p0(i));
    b.extend(p1(i));
    b.extend(p2(i));
    return b;
  }
};

struct Triangle {
  static constexpr PrimTag tag = PrimTag::kTriangle;
  static constexpr std::string_view keyword = "";  // no scene command: made by `mesh`
  static constexpr int param_count = 0;
  using Table = TriangleTable;
};

namespace detail {
// The watertight ray/triangle test of Woop, Benthin and Wald (2013, JCGT 2(1)), in double:
// vertices relative to the origin, axes permuted so that the largest |d| component is z
// (ties to the lowest axis; x and y swapped when d_z < 0 to keep the winding), sheared so the
// ray is +z. Edge functions U, V, W with their exact sign (difference of products); the hit
// needs all ≥ 0 or all ≤ 0 and det = U + V + W ≠ 0. Returns false on a miss.
struct WoopRef {
  double u, v, w, det, t;
};
inline bool woop_ref(const TriangleTable& tri, uint32_t i, const Rayd& ray, WoopRef& out) {
  Vec3d p0(tri.p0(i)), p1(tri.p1(i)), p2(tri.p2(i));
  if (length_squared(cross(p1 - p0, p2 - p0)) == 0) return false;  // zero area (hard-cases T4)
  int kz = max_dimension(abs(ray.d));
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (ray.d[kz] < 0) std::swap(kx, ky);
  double sx = ray.d[kx] / ray.d[kz], sy = ray.d[ky] / ray.d[kz], sz = 1.0 / ray.d[kz];
  Vec3d a = p0 - ray.o, b = p1 - ray.o, c = p2 - ray.o;
  double ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
  double bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
  double cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
  out.u = difference_of_products(cx, by, cy, bx);
  out.v = difference_of_products(ax, cy, ay, cx);
  out.w = difference_of_products(bx, ay, by, ax);
  if ((out.u < 0 || out.v < 0 || out.w < 0) && (out.u > 0 || out.v > 0 || out.w > 0)) return false;
  out.det = out.u + out.v + out.w;
  if (out.det == 0) return false;
  double t_scaled = out.u * sz * a[kz] + out.v * sz * b[kz] + out.w * sz * c[kz];
  out.t = t_scaled / out.det;
  return true;
}
}  // namespace detail

inline double intersect_ref(const TriangleTable& tri, uint32_t i, const Rayd& ray) {
  detail::WoopRef w;
  if (!detail::woop_ref(tri, i, ray, w) || !(w.t > ray.tmin && w.t < ray.tmax))
    return std::numeric_limits<double>::infinity();
  return w.t;
}

// The point from the barycentrics (pbrt-v4 Triangle::InteractionFromIntersection), the
// geometric normal by the winding, the shading normal interpolated from the vertex normals.
inline Surface surface_ref(const TriangleTable& tri, uint32_t i, const Rayd& ray, double t) {
  Vec3d p0(tri.p0(i)), p1(tri.p1(i)), p2(tri.p2(i));
  Vec3d ng = normalize(cross(p1 - p0, p2 - p0));
  detail::WoopRef w;
  Rayd unbounded = ray;
  unbounded.tmin = -std::numeric_limits<double>::infinity();
  unbounded.tmax = std::numeric_limits<double>::infinity();
  if (!detail::woop_ref(tri, i, unbounded, w)) return {ray.at(t), ng, ng};
  double b0 = w.u / w.det, b1 = w.v / w.det, b2 = w.w / w.det;
  Vec3d p = b0 * p0 + b1 * p1 + b2 * p2;
  Vec3d ns = b0 * Vec3d(tri.n0(i)) + b1 * Vec3d(tri.n1(i)) + b2 * Vec3d(tri.n2(i));
  double len = length(ns);
  return {p, ng, len > 0 && std::isfinite(len) ? ns / len : ng};
}

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
// (hard-cases T2).
template <class A>
inline simd::Floats<A> difference_of_products_lanes(const simd::Floats<A>& a,
                                                    const simd::Floats<A>& b,
                                                    const simd::Floats<A>& c,
                                                    const simd::Floats<A>& d) {
  simd::Floats<A> cd = c * d;
  simd::Floats<A> err = simd::fma<A>(-c, d, cd);
  return simd::fma<A>(a, b, -cd) + err;
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
    auto has_neg = (u < zero) | (v < zero) | (e < zero);
    auto has_pos = (u > zero) | (v > zero) | (e > zero);
    F det = u + v + e;
    simd::Mask<A> hit = rows.mask() & (!(has_neg & has_pos)) & (det != zero);
    if (simd::none<A>(hit)) continue;
    F t = (u * az + v * bz + e * cz) / det;
    commit_hit<A>(t, hit & (t > r.tmin) & (t < h.t), rows.bits(PrimTag::kTriangle), h);
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

}  // namespace raylane
