// Spheres: `sphere cx cy cz r`. The table, its reference kernel and its packet kernel.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "raylane/core/bounds3.h"
#include "raylane/core/ray.h"
#include "raylane/prims/prim_ref.h"
#include "raylane/prims/solid.h"
#include "raylane/prims/surface.h"
#include "raylane/prims/table_util.h"
#include "raylane/trace/packet.h"

namespace raylane {

struct SphereTable {
  std::vector<float> cx, cy, cz, r;
  std::vector<uint32_t> material;

  auto columns() { return std::tie(cx, cy, cz, r, material); }
  std::size_t size() const { return r.size(); }
  Vec3f center(uint32_t i) const { return {cx[i], cy[i], cz[i]}; }

  // p = (cx, cy, cz, r); r must be > 0 after rounding to float.
  std::optional<ParamError> append(std::span<const double, 4> p, uint32_t mat) {
    float radius = float(p[3]);
    if (!(radius > 0.0f)) return ParamError{3, "sphere radius must be > 0"};
    cx.push_back(float(p[0]));
    cy.push_back(float(p[1]));
    cz.push_back(float(p[2]));
    r.push_back(radius);
    material.push_back(mat);
    return std::nullopt;
  }

  Bounds3f bounds(uint32_t i) const {
    Vec3d c(center(i));
    Vec3d rr(r[i], r[i], r[i]);
    return round_out(Bounds3d(c - rr, c + rr));
  }
};

struct Sphere {
  static constexpr PrimTag tag = PrimTag::kSphere;
  static constexpr std::string_view keyword = "sphere";
  static constexpr int param_count = 4;
  using Table = SphereTable;
};

// The reference kernel, in double on the table's floats. The discriminant is the squared
// distance between the ray's line and the centre subtracted from r² (Hearn–Baker), so a far,
// small sphere does not cancel to nothing (hard-cases S1).
inline double intersect_ref(const SphereTable& s, uint32_t i, const Rayd& ray) {
  constexpr double kMiss = std::numeric_limits<double>::infinity();
  Vec3d c(s.center(i));
  double r = s.r[i];
  Vec3d f = ray.o - c;
  double a = dot(ray.d, ray.d), b = dot(f, ray.d);
  Vec3d l = f - (b / a) * ray.d;
  double disc = r * r - dot(l, l);
  if (!(disc >= 0)) return kMiss;
  double t0, t1;
  solve_quadratic(a, b, dot(f, f) - r * r, a * disc, t0, t1);
  return first_in_range(t0, t1, ray);
}

// The hit point is projected back onto the sphere (pbrt-v4 Sphere::Intersect), so its error
// is a few ulps of the radius, not of the distance travelled.
inline Surface surface_ref(const SphereTable& s, uint32_t i, const Rayd& ray, double t) {
  Vec3d c(s.center(i));
  Vec3d n = normalize(ray.at(t) - c);
  return {c + n * double(s.r[i]), n, n};
}

// The packet kernel, in float, with rays or rows in the lanes (`Rows`, trace/packet.h).
// Discriminant in the Hearn–Baker form r² − |f − (f·d/d·d)·d|² and roots by the Press form, as in
// the reference (Haines et al. 2019, Ray Tracing Gems ch. 7). Updates h where a lane finds a nearer
// hit.
template <class A, class Rows>
[[gnu::always_inline]] inline void intersect_packet(const SphereTable& s, Rows rows,
                                                    const RayPacket<A>& r, HitPacket<A>& h) {
  using F = simd::Floats<A>;
  const F dd = r.dx * r.dx + r.dy * r.dy + r.dz * r.dz;
  for (; rows.more(); rows.next()) {
    F fx = r.ox - rows.col(s.cx), fy = r.oy - rows.col(s.cy), fz = r.oz - rows.col(s.cz);
    F b = fx * r.dx + fy * r.dy + fz * r.dz;
    F k = b / dd;
    F lx = fx - k * r.dx, ly = fy - k * r.dy, lz = fz - k * r.dz;
    F radius = rows.col(s.r), rr = radius * radius;
    F disc = rr - (lx * lx + ly * ly + lz * lz);
    simd::Mask<A> hit = rows.mask() & (disc >= F(0.0f));
    if (simd::none<A>(hit)) continue;
    F sq = xsimd::sqrt(dd * disc);
    F q = -(b + simd::select<A>(b < F(0.0f), -sq, sq));
    F c = fx * fx + fy * fy + fz * fz - rr;
    F t0 = c / q, t1 = q / dd;
    F tn = simd::select<A>(t0 < t1, t0, t1), tf = simd::select<A>(t0 < t1, t1, t0);
    commit_solid_hit<A>(tn, tf, r, hit, rows.bits(PrimTag::kSphere), h);
  }
}

}  // namespace raylane
