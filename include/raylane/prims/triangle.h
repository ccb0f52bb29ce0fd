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

// Per-lane setup of the watertight test: the axis of largest |d| becomes z, x and y follow
// cyclically (swapped when d_z < 0, to keep the winding), and the shear that maps d to +z
// (Woop, Benthin and Wald 2013, §3). Computed once per run of triangles.
template <class A>
struct WoopSetup {
  using F = simd::Floats<A>;
  simd::Mask<A> x_is[3], y_is[3], z_is[3];  // which world axis each sheared axis reads
  F sx, sy, sz;

  static F pick(const simd::Mask<A>* is, const F& x, const F& y, const F& z) {
    return simd::select<A>(is[0], x, simd::select<A>(is[1], y, z));
  }

  explicit WoopSetup(const RayPacket<A>& r) {
    F ax = xsimd::abs(r.dx), ay = xsimd::abs(r.dy), az = xsimd::abs(r.dz);
    // kz = argmax |d|, ties to the lowest axis, as in the reference.
    z_is[0] = (ax >= ay) & (ax >= az);
    z_is[1] = (!z_is[0]) & (ay >= az);
    z_is[2] = (!z_is[0]) & (!z_is[1]);
    // kx = kz + 1, ky = kz + 2 (mod 3); swapped when d[kz] < 0.
    simd::Mask<A> kx_base[3] = {z_is[2], z_is[0], z_is[1]};
    simd::Mask<A> ky_base[3] = {z_is[1], z_is[2], z_is[0]};
    F dz = pick(z_is, r.dx, r.dy, r.dz);
    auto flip = dz < F(0.0f);
    for (int k = 0; k < 3; ++k) {
      x_is[k] = (kx_base[k] & (!flip)) | (ky_base[k] & flip);
      y_is[k] = (ky_base[k] & (!flip)) | (kx_base[k] & flip);
    }
    F dx = pick(x_is, r.dx, r.dy, r.dz), dy = pick(y_is, r.dx, r.dy, r.dz);
    sz = F(1.0f) / dz;
    sx = dx * sz;
    sy = dy * sz;
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

// The packet kernel: the watertight test in float, per lane (Woop et al. 2013): vertices
// relative to the origin, permuted and sheared; edge functions U, V, W with their exact sign;
// accept all ≥ 0 or all ≤ 0 with det ≠ 0; t = T/det.
template <class A>
void intersect_packet(const TriangleTable& tri, uint32_t begin, uint32_t end, const RayPacket<A>& r,
                      const simd::Mask<A>& lanes, HitPacket<A>& h) {
  using F = simd::Floats<A>;
  const WoopSetup<A> w(r);
  const F zero(0.0f);
  auto sheared = [&](float px, float py, float pz, F& x, F& y, F& z) {
    F ax = F(px) - r.ox, ay = F(py) - r.oy, az = F(pz) - r.oz;
    F kz = WoopSetup<A>::pick(w.z_is, ax, ay, az);
    x = simd::fma<A>(-w.sx, kz, WoopSetup<A>::pick(w.x_is, ax, ay, az));
    y = simd::fma<A>(-w.sy, kz, WoopSetup<A>::pick(w.y_is, ax, ay, az));
    z = w.sz * kz;
  };
  for (uint32_t i = begin; i < end; ++i) {
    F ax, ay, az, bx, by, bz, cx, cy, cz;
    sheared(tri.p0x[i], tri.p0y[i], tri.p0z[i], ax, ay, az);
    sheared(tri.p1x[i], tri.p1y[i], tri.p1z[i], bx, by, bz);
    sheared(tri.p2x[i], tri.p2y[i], tri.p2z[i], cx, cy, cz);
    F u = difference_of_products_lanes<A>(cx, by, cy, bx);
    F v = difference_of_products_lanes<A>(ax, cy, ay, cx);
    F e = difference_of_products_lanes<A>(bx, ay, by, ax);
    auto has_neg = (u < zero) | (v < zero) | (e < zero);
    auto has_pos = (u > zero) | (v > zero) | (e > zero);
    F det = u + v + e;
    simd::Mask<A> hit = lanes & (!(has_neg & has_pos)) & (det != zero);
    if (simd::none<A>(hit)) continue;
    F t = (u * az + v * bz + e * cz) / det;
    commit_hit<A>(t, hit & (t > r.tmin) & (t < h.t), prim_bits(PrimTag::kTriangle, i), h);
  }
}

}  // namespace raylane
