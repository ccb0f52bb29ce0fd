// Mesh triangles (made by the `mesh` command). The table, the kind's traits and its reference
// kernel; the SIMD kernel is in triangle_packet.h.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "raylane/core/bounds3.h"
#include "raylane/core/float_util.h"
#include "raylane/core/prim_ref.h"
#include "raylane/core/ray.h"
#include "raylane/prims/surface.h"
#include "raylane/prims/table_util.h"

namespace raylane {

// Vertices as given (the watertight test works on vertices relative to the ray origin, so it
// wants p0, p1, p2 rather than edges), and per-vertex shading normals. Texture coordinates of
// the vertices are optional columns: empty unless some mesh has UVs and a textured material
// (Scene::drop_unused_uvs empties them again if no triangle's material is textured); rows of
// meshes without UVs hold (0, 0).
struct TriangleTable {
  std::vector<float> p0x, p0y, p0z, p1x, p1y, p1z, p2x, p2y, p2z;
  std::vector<float> n0x, n0y, n0z, n1x, n1y, n1z, n2x, n2y, n2z;
  std::vector<uint32_t> material;
  std::vector<float> t0u, t0v, t1u, t1v, t2u, t2v;

  auto columns() {
    return std::tie(p0x, p0y, p0z, p1x, p1y, p1z, p2x, p2y, p2z, n0x, n0y, n0z, n1x, n1y, n1z, n2x,
                    n2y, n2z, material);
  }
  auto optional_columns() { return std::tie(t0u, t0v, t1u, t1v, t2u, t2v); }
  bool has_uv() const { return uv_columns_; }
  // UV columns for every row so far, (0, 0) at each vertex; rows appended later get theirs.
  void add_uv_columns() {
    uv_columns_ = true;
    std::apply([&](auto&... c) { (c.assign(size(), 0.0f), ...); }, optional_columns());
  }
  void drop_uv_columns() {
    uv_columns_ = false;
    std::apply([](auto&... c) { (std::vector<float>().swap(c), ...); }, optional_columns());
  }
  std::size_t size() const { return p0x.size(); }
  glm::vec3 p0(uint32_t i) const { return {p0x[i], p0y[i], p0z[i]}; }
  glm::vec3 p1(uint32_t i) const { return {p1x[i], p1y[i], p1z[i]}; }
  glm::vec3 p2(uint32_t i) const { return {p2x[i], p2y[i], p2z[i]}; }
  glm::vec3 n0(uint32_t i) const { return {n0x[i], n0y[i], n0z[i]}; }
  glm::vec3 n1(uint32_t i) const { return {n1x[i], n1y[i], n1z[i]}; }
  glm::vec3 n2(uint32_t i) const { return {n2x[i], n2y[i], n2z[i]}; }

  // A row; its UVs (if the table has UV columns) are `uv`, or (0, 0) without.
  void append(const std::array<glm::vec3, 3>& p, const std::array<glm::vec3, 3>& n, uint32_t mat,
              const std::array<TexCoord, 3>* uv = nullptr) {
    p0x.push_back(p[0].x), p0y.push_back(p[0].y), p0z.push_back(p[0].z);
    p1x.push_back(p[1].x), p1y.push_back(p[1].y), p1z.push_back(p[1].z);
    p2x.push_back(p[2].x), p2y.push_back(p[2].y), p2z.push_back(p[2].z);
    n0x.push_back(n[0].x), n0y.push_back(n[0].y), n0z.push_back(n[0].z);
    n1x.push_back(n[1].x), n1y.push_back(n[1].y), n1z.push_back(n[1].z);
    n2x.push_back(n[2].x), n2y.push_back(n[2].y), n2z.push_back(n[2].z);
    material.push_back(mat);
    if (!uv_columns_) return;
    std::array<TexCoord, 3> t = uv ? *uv : std::array<TexCoord, 3>{};
    t0u.push_back(float(t[0].u)), t0v.push_back(float(t[0].v));
    t1u.push_back(float(t[1].u)), t1v.push_back(float(t[1].v));
    t2u.push_back(float(t[2].u)), t2v.push_back(float(t[2].v));
  }

  // Vertices are exact floats: their min and max need no rounding.
  Bounds3f bounds(uint32_t i) const {
    Bounds3f b;
    b.extend(p0(i));
    b.extend(p1(i));
    b.extend(p2(i));
    return b;
  }

 private:
  bool uv_columns_ = false;
};

struct Triangle {
  using Table = TriangleTable;
  static constexpr std::string_view name = "triangle", plural = "triangles";
  static constexpr std::string_view keyword = "";  // no scene command: made by `mesh`
  static constexpr int param_count = 0;
  static constexpr bool two_sided = true;  // a mesh is a surface: both sides emit and reflect
  // Measured with bench_trace (bench/README.md): triangles are cheap enough that leaves of up
  // to 8 pay, for packets and single rays alike (1.31M mesh: 1.2-1.3x); the quadrics and
  // boxes of the lattice lose speed with bigger leaves, so they keep cost 1.
  static constexpr double sah_test_cost = 0.3;
  // Surfaces one by one (surface_ref): the watertight test's difference of products needs
  // a fused multiply-add, which SSE4.2 lanes lack, and meshes are a small share of the course
  // scene's hits.
  static constexpr bool surface_in_lanes = false;
  static constexpr bool surface_in_float_lanes = false;
  static double area(const Table& t, uint32_t i);
  // A uniform point on the surface and its outward normal; u_part picks the part (a box's
  // face, a cylinder's side or cap) in proportion to its area.
  static AreaSample sample_area(const Table& t, uint32_t i, double u_part, double u1, double u2);
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
  glm::dvec3 p0(tri.p0(i)), p1(tri.p1(i)), p2(tri.p2(i));
  if (length_squared(cross(p1 - p0, p2 - p0)) == 0)
    return false;  // zero area (docs/hard-cases.md T4)
  int kz = max_dimension(abs(ray.d));
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (ray.d[kz] < 0) std::swap(kx, ky);
  double sx = ray.d[kx] / ray.d[kz], sy = ray.d[ky] / ray.d[kz], sz = 1.0 / ray.d[kz];
  glm::dvec3 a = p0 - ray.o, b = p1 - ray.o, c = p2 - ray.o;
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
  glm::dvec3 p0(tri.p0(i)), p1(tri.p1(i)), p2(tri.p2(i));
  glm::dvec3 ng = normalize(cross(p1 - p0, p2 - p0));
  detail::WoopRef w;
  Rayd unbounded = ray;
  unbounded.tmin = -std::numeric_limits<double>::infinity();
  unbounded.tmax = std::numeric_limits<double>::infinity();
  if (!detail::woop_ref(tri, i, unbounded, w)) return {ray.at(t), ng, ng};
  double b0 = w.u / w.det, b1 = w.v / w.det, b2 = w.w / w.det;
  glm::dvec3 p = b0 * p0 + b1 * p1 + b2 * p2;
  glm::dvec3 ns =
      b0 * glm::dvec3(tri.n0(i)) + b1 * glm::dvec3(tri.n1(i)) + b2 * glm::dvec3(tri.n2(i));
  double len = length(ns);
  return {p, ng, len > 0 && std::isfinite(len) ? ns / len : ng};
}

// What a triangle adds to the bound on its hit point's error (float_hit_point_bound) for the
// render's offsets: the float kernel decides which side of the plane a ray's origin lies on with
// an error that grows with the vertices' magnitudes, not with |o| + |t·d| (docs/hard-cases.md
// R2). pbrt-v4 §6.8.5 bounds the barycentric point by γ7·Σ|bᵢ·pᵢ|; with the barycentrics in
// [0, 1] summing to 1, the largest vertex coordinate per component bounds the sum.
inline glm::dvec3 triangle_vertex_bound(const TriangleTable& tri, uint32_t i) {
  const glm::dvec3 m =
      max(max(abs(glm::dvec3(tri.p0(i))), abs(glm::dvec3(tri.p1(i)))), abs(glm::dvec3(tri.p2(i))));
  return m * gamma_float(7);
}

// The vertices' UVs interpolated with the barycentrics of the hit point, found from the point
// by least squares on the edges (exact for a point in the plane; the point of a hit is within
// rounding of it). (0, 0) for a table without UVs.
inline TexCoord texcoord_ref(const TriangleTable& tri, uint32_t i, const Surface& s) {
  if (!tri.has_uv()) return {};
  glm::dvec3 p0(tri.p0(i)), e1 = glm::dvec3(tri.p1(i)) - p0, e2 = glm::dvec3(tri.p2(i)) - p0,
                            q = s.p - p0;
  double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
  double q1 = dot(q, e1), q2 = dot(q, e2);
  double det = d11 * d22 - d12 * d12;
  if (!(det > 0)) return {tri.t0u[i], tri.t0v[i]};
  double b1 = (d22 * q1 - d12 * q2) / det, b2 = (d11 * q2 - d12 * q1) / det, b0 = 1 - b1 - b2;
  return {b0 * tri.t0u[i] + b1 * tri.t1u[i] + b2 * tri.t2u[i],
          b0 * tri.t0v[i] + b1 * tri.t1v[i] + b2 * tri.t2v[i]};
}

}  // namespace raylane
