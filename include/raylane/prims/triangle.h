// Mesh triangles (made by the `mesh` command). The table, the kind's traits and its reference
// kernel; the SIMD kernel is in triangle_packet.h.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "raylane/core/bounds3.h"
#include "raylane/core/float_util.h"
#include "raylane/core/numbers.h"
#include "raylane/core/prim_ref.h"
#include "raylane/core/ray.h"
#include "raylane/core/ray_offset.h"
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
  // The render's surfaces in float lanes with their bounds (triangle_packet.h); a hit record's
  // one by one (surface_ref): it has two normals, which SurfaceLanes does not.
  static constexpr bool surface_in_lanes = false;
  static constexpr bool surface_in_float_lanes = true;
  static constexpr bool has_shading_normal = true;  // interpolated from the vertex normals
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

// A triangle hit's surface over the number type (double: the reference; float and float lanes:
// the render's columns, prims/triangle_packet.h), by barycentric reconstruction (Pharr, Jakob
// and Humphreys, pbrt-v4 §6.8.5): the point is b0·p0 + b1·p1 + b2·p2, so that it lies on the
// triangle's plane within a few roundoffs of the vertices whatever the error of t. The
// barycentrics are the edge functions' shares (Woop et al. 2013) written as triple products with
// the direction, d·(c × b) and its rotations, of the vertices relative to q = o + t·d: a triple
// product with d does not change when q moves along d, so t's error does not enter them, and
// relative to a point on the triangle the vertices are as small as its edges, where relative to
// the origin the cross products would cancel (the sheared form of the hit test avoids the same).
// Where the barycentrics are not numbers (a degenerate determinant, or an overflow at huge
// coordinates) the point is q itself. The geometric normal is by the winding, its edges' cross
// product scaled by its largest component first so that squaring it neither overflows nor
// underflows at float; the shading normal is the vertex normals interpolated, or the geometric
// one where that has no direction.
template <class V3>
struct TriangleSurface {
  V3 p, ng, ns;
  // |b0·p0| + |b1·p1| + |b2·p2| per component: what triangle_point_bound scales; not a number
  // where p is q.
  V3 weight;
};

template <class N, class V3>
TriangleSurface<V3> triangle_surface(const std::array<V3, 3>& v, const std::array<V3, 3>& vn,
                                     const V3& o, const V3& d, const N& t) {
  using K = Num<N>;
  auto minus = [](const V3& a, const V3& b) { return V3{a.x - b.x, a.y - b.y, a.z - b.z}; };
  auto cross3 = [](const V3& a, const V3& b) {
    return V3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  };
  auto dot3 = [](const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
  auto scaled = [](const V3& a, const N& s) { return V3{a.x * s, a.y * s, a.z * s}; };
  auto unit = [&](const V3& a) { return scaled(a, N(1.0) / K::sqrt(dot3(a, a))); };
  // q relative to p0 first, (o − p0) + t·d: its rounding then scales with the ray's segment,
  // not with |q| (a mesh far from the origin, a short bounce ray).
  const V3 op0 = minus(o, v[0]);
  const V3 q0{op0.x + d.x * t, op0.y + d.y * t, op0.z + d.z * t};
  const V3 e01 = minus(v[1], v[0]), e02 = minus(v[2], v[0]);
  const V3 a{K::negate(q0.x), K::negate(q0.y), K::negate(q0.z)}, b = minus(e01, q0),
                                                                 c = minus(e02, q0);
  const N e0 = dot3(d, cross3(c, b)), e1 = dot3(d, cross3(a, c)), e2 = dot3(d, cross3(b, a));
  const N sum = e0 + e1 + e2;
  const N inv = N(1.0) / sum;
  const N b0 = e0 * inv, b1 = e1 * inv, b2 = e2 * inv;
  auto blend = [&](const V3& x0, const V3& x1, const V3& x2) {
    return V3{b0 * x0.x + b1 * x1.x + b2 * x2.x, b0 * x0.y + b1 * x1.y + b2 * x2.y,
              b0 * x0.z + b1 * x1.z + b2 * x2.z};
  };
  auto weigh = [&](const N& x0, const N& x1, const N& x2) {
    return K::abs(b0 * x0) + K::abs(b1 * x1) + K::abs(b2 * x2);
  };
  // The barycentrics stand where their sum did not cancel (its rounding is then within two
  // roundoffs of it: they sum to 1 within a few) and 1/sum is a normal float; a grazing ray or
  // a hit found just outside the triangle's edge by rounding can give shares of both signs
  // whose sum is mostly cancellation.
  const auto shares_agree = K::abs(sum) >= N(0.5) * (K::abs(e0) + K::abs(e1) + K::abs(e2));
  const V3 w{weigh(v[0].x, v[1].x, v[2].x), weigh(v[0].y, v[1].y, v[2].y),
             weigh(v[0].z, v[1].z, v[2].z)};
  const auto reconstructed =
      shares_agree & (K::abs(sum) < N(0x1p126)) & (w.x + w.y + w.z < N(HUGE_VAL));  // NaN: false
  const N no(std::numeric_limits<double>::quiet_NaN());
  TriangleSurface<V3> s;
  s.weight = V3{K::select(reconstructed, w.x, no), K::select(reconstructed, w.y, no),
                K::select(reconstructed, w.z, no)};
  const V3 bp = blend(v[0], v[1], v[2]);
  const V3 q{v[0].x + q0.x, v[0].y + q0.y, v[0].z + q0.z};
  s.p = V3{K::select(reconstructed, bp.x, q.x), K::select(reconstructed, bp.y, q.y),
           K::select(reconstructed, bp.z, q.z)};
  // Each component divided by the largest, not multiplied by its reciprocal, which overflows
  // for a float cross product below 2^-128 (edges of about 1e-20 near the origin). Where the
  // cross product has no direction in the number type (zero, or infinite for huge edges), the
  // normal faces the ray.
  const V3 g = cross3(e01, e02);
  const N largest = K::max(K::max(K::abs(g.x), K::abs(g.y)), K::abs(g.z));
  const auto has_normal = (largest > N(0.0)) & (largest < N(HUGE_VAL));
  const V3 facing = unit(V3{K::negate(d.x), K::negate(d.y), K::negate(d.z)});
  const V3 gn = unit(V3{g.x / largest, g.y / largest, g.z / largest});
  s.ng = V3{K::select(has_normal, gn.x, facing.x), K::select(has_normal, gn.y, facing.y),
            K::select(has_normal, gn.z, facing.z)};
  const V3 m = blend(vn[0], vn[1], vn[2]);
  const N len = K::sqrt(dot3(m, m));
  const auto usable = (len > N(0.0)) & (len < N(HUGE_VAL));
  const N inv_len = N(1.0) / len;
  s.ns = V3{K::select(usable, m.x * inv_len, s.ng.x), K::select(usable, m.y * inv_len, s.ng.y),
            K::select(usable, m.z * inv_len, s.ng.z)};
  return s;
}

// A bound on the error of triangle_surface's point computed in float, for the offset along its
// normal: γ7·(|b0·p0| + |b1·p1| + |b2·p2|) (pbrt-v4 §6.8.5, eq. 6.33, which also covers the
// barycentrics' own rounding: they sum to 1 within a few roundoffs, and any that do put the
// point on the plane within it). The constant carries 2^-20 more for this product's and sum's
// own float roundings. Where the point is q = o + t·d instead, the hit point's bound
// (float_hit_point_bound) and the vertices' (triangle_vertex_bound's γ7 of the largest).
template <class N, class V3>
V3 triangle_point_bound(const TriangleSurface<V3>& s, const std::array<V3, 3>& v, const V3& o,
                        const V3& d, const N& t) {
  using K = Num<N>;
  const N gamma7(gamma_float(7) * (1 + 0x1p-20));
  const auto reconstructed = s.weight.x + s.weight.y + s.weight.z < N(HUGE_VAL);  // NaN: false
  const V3 along = float_hit_point_bound<N>(o, d, t, s.p);
  auto one = [&](const N& w, const N& x0, const N& x1, const N& x2, const N& ak) {
    const N largest = K::max(K::max(K::abs(x0), K::abs(x1)), K::abs(x2));
    return K::select(reconstructed, w * gamma7, ak + largest * gamma7);
  };
  return V3{one(s.weight.x, v[0].x, v[1].x, v[2].x, along.x),
            one(s.weight.y, v[0].y, v[1].y, v[2].y, along.y),
            one(s.weight.z, v[0].z, v[1].z, v[2].z, along.z)};
}

inline Surface surface_ref(const TriangleTable& tri, uint32_t i, const Rayd& ray, double t) {
  const std::array<glm::dvec3, 3> v{glm::dvec3(tri.p0(i)), glm::dvec3(tri.p1(i)),
                                    glm::dvec3(tri.p2(i))};
  const std::array<glm::dvec3, 3> vn{glm::dvec3(tri.n0(i)), glm::dvec3(tri.n1(i)),
                                     glm::dvec3(tri.n2(i))};
  const TriangleSurface<glm::dvec3> s = triangle_surface<double>(v, vn, ray.o, ray.d, t);
  return {s.p, s.ng, s.ns};
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
