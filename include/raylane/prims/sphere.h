// Spheres: `sphere cx cy cz r`. The table, the kind's traits and its reference kernel; the SIMD
// kernel is in sphere_packet.h.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "raylane/core/bounds3.h"
#include "raylane/core/float_util.h"
#include "raylane/core/numbers.h"
#include "raylane/core/prim_ref.h"
#include "raylane/core/ray.h"
#include "raylane/core/warps.h"
#include "raylane/prims/solid.h"
#include "raylane/prims/surface.h"
#include "raylane/prims/table_util.h"

namespace raylane {

struct SphereTable {
  std::vector<float> cx, cy, cz, r;
  std::vector<uint32_t> material;

  auto columns() { return std::tie(cx, cy, cz, r, material); }
  std::size_t size() const { return r.size(); }
  glm::vec3 center(uint32_t i) const { return {cx[i], cy[i], cz[i]}; }

  // p = (cx, cy, cz, r); r must be > 0 after rounding to float, and c ± r finite in float.
  std::optional<ParamError> append(std::span<const double, 4> p, uint32_t mat) {
    float radius = float(p[3]);
    if (!(radius > 0.0f))
      return ParamError{3, p[3] > 0 ? "sphere radius rounds to 0 in single precision; it must "
                                      "be > 0 after rounding (at least about 1.4e-45)"
                                    : "sphere radius must be > 0"};
    for (int k = 0; k < 3; ++k)  // its bounds, centre ± radius, must be finite floats
      if (!std::isfinite(float(std::abs(p[k]) + double(radius))))
        return ParamError{3, "sphere reaches beyond float (the largest is about 3.4e38)"};
    cx.push_back(float(p[0]));
    cy.push_back(float(p[1]));
    cz.push_back(float(p[2]));
    r.push_back(radius);
    material.push_back(mat);
    return std::nullopt;
  }

  Bounds3f bounds(uint32_t i) const {
    glm::dvec3 c(center(i));
    glm::dvec3 rr(r[i], r[i], r[i]);
    return round_out(Bounds3d(c - rr, c + rr));
  }
};

struct Sphere {
  using Table = SphereTable;
  static constexpr std::string_view name = "sphere", plural = "spheres", keyword = "sphere";
  static constexpr int param_count = 4;
  static constexpr bool two_sided = false;
  // A node visit tests two child boxes; the sphere kernel (sphere_packet.h) is one dot-product
  // chain and a division before its early out, about a third of that. At 1.0 the SAH made leaves
  // of one sphere, most of a sphere's bytes then nodes; at 0.3 the sphereflake traces primary,
  // shadow and diffuse rays faster, builds faster and needs fewer bytes per sphere than Embree
  // (the figures: bench/README.md, "The SAH sweep, a sphere's test cost, memory per sphere").
  static constexpr double sah_test_cost = 0.3;
  // The SIMD tracer computes its hits' surfaces in double lanes (sphere_packet.h, surface_lanes).
  static constexpr bool surface_in_lanes = true;
  // The render's float columns take its surfaces in float lanes, with their error bounds
  // (sphere_packet.h, surface_float_lanes).
  static constexpr bool surface_in_float_lanes = true;
  static double area(const Table& t, uint32_t i);
  // A uniform point on the surface and its outward normal; u_part picks the part (a box's
  // face, a cylinder's side or cap) in proportion to its area.
  static AreaSample sample_area(const Table& t, uint32_t i, double u_part, double u1, double u2);
  // Seen from outside: a direction uniform in the cone the sphere subtends (pbrt-v4
  // Sphere::Sample), and that cone's solid angle; nothing from inside (area sampling then).
  static std::optional<SubtendedSample> sample_subtended(const Table& t, uint32_t i,
                                                         const glm::dvec3& ref, double u1,
                                                         double u2);
  static std::optional<double> subtended_solid_angle(const Table& t, uint32_t i,
                                                     const glm::dvec3& ref);
  // The course's `lit` view lights from an emitting sphere's centre.
  static glm::dvec3 point_light(const Table& t, uint32_t i) { return glm::dvec3(t.center(i)); }
};

// Sphere's emitter sampling for a sphere of centre c and radius r (sphere.cpp), shared with the
// moving sphere, whose centre is the one at the path's time.
AreaSample sample_sphere_area(const glm::dvec3& c, double r, double u1, double u2);
std::optional<SubtendedSample> sample_sphere_cone(const glm::dvec3& c, double r,
                                                  const glm::dvec3& ref, double u1, double u2);
std::optional<double> sphere_cone_solid_angle(const glm::dvec3& c, double r, const glm::dvec3& ref);

// The reference kernel of a sphere of centre c and radius r, in double. The discriminant is the
// squared distance between the ray's line and the centre subtracted from r² (Hearn–Baker), so a
// far, small sphere does not cancel to nothing (docs/hard-cases.md S1).
inline double intersect_sphere_ref(const glm::dvec3& c, double r, const Rayd& ray) {
  constexpr double kMiss = std::numeric_limits<double>::infinity();
  glm::dvec3 f = ray.o - c;
  double a = dot(ray.d, ray.d), b = dot(f, ray.d);
  glm::dvec3 l = f - (b / a) * ray.d;
  double disc = r * r - dot(l, l);
  if (!(disc >= 0)) return kMiss;
  double t0, t1;
  solve_quadratic(a, b, dot(f, f) - r * r, a * disc, t0, t1);
  return first_in_range(t0, t1, ray);
}

// The reference kernel, in double on the table's floats.
inline double intersect_ref(const SphereTable& s, uint32_t i, const Rayd& ray) {
  return intersect_sphere_ref(glm::dvec3(s.center(i)), s.r[i], ray);
}

// The surface at a hit, written once over the number type N (core/numbers.h) and its 3-vector
// V3: double for surface_ref, double lanes for the SIMD tracer's hit records, float lanes for the
// render's float columns (sphere_packet.h). The hit point o + t·d is projected back onto the
// sphere from its centre (pbrt-v4 Sphere::Intersect), so its error is a few ulps of the radius,
// not of the distance travelled: n = (p − c)/|p − c| as core/vec_math.h's normalize, then
// c + n·r. `offset` is n·r, the point's part that carries that error (sphere_point_bound).
template <class V3>
struct SphereSurface {
  V3 p, n, offset;
};
template <class N, class V3>
SphereSurface<V3> sphere_surface(const V3& c, const N& r, const V3& o, const V3& d, const N& t) {
  const V3 v{o.x + d.x * t - c.x, o.y + d.y * t - c.y, o.z + d.z * t - c.z};
  const N len = Num<N>::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  const V3 n{v.x / len, v.y / len, v.z / len}, offset{n.x * r, n.y * r, n.z * r};
  return {V3{c.x + offset.x, c.y + offset.y, c.z + offset.z}, n, offset};
}

// A bound on the error of sphere_surface's point computed in float, for the offset along its
// normal: the reprojected offset n·r within γ6 of its exact length along the normal (pbrt-v4
// §6.8.5 bounds the reprojected point by γ5|p| about the centre; one more for our division per
// component), plus the rounding of c + n·r (one roundoff of |p|; c is the table's own float).
// Both constants carry 2^-20 more for this sum's own float roundings. Not a bound on where along
// the sphere the point lies: o + t·d's rounding before the reprojection may slide it sideways by
// more, as it may slide the double reference's, and no offset along the normal needs to cover
// that.
template <class N, class V3>
V3 sphere_point_bound(const V3& p, const V3& offset) {
  using K = Num<N>;
  const N reprojected(gamma_float(6) * (1 + 0x1p-20)), own(kFloatUnitRoundoff * (1 + 0x1p-20));
  auto one = [&](const N& pk, const N& ok) { return K::abs(ok) * reprojected + K::abs(pk) * own; };
  return V3{one(p.x, offset.x), one(p.y, offset.y), one(p.z, offset.z)};
}

inline Surface surface_ref(const SphereTable& s, uint32_t i, const Rayd& ray, double t) {
  const SphereSurface<glm::dvec3> x =
      sphere_surface<double>(glm::dvec3(s.center(i)), double(s.r[i]), ray.o, ray.d, t);
  return {x.p, x.n, x.n};
}

// u = φ/2π with φ = atan2(y, x) in [0, 2π), v = 1 − θ/π with θ from +Z, of a unit direction d
// from the centre in world axes.
inline TexCoord sphere_texcoord(const glm::dvec3& d) {
  double phi = std::atan2(d.y, d.x);
  if (phi < 0) phi += 2 * kPi;
  double u = phi / (2 * kPi);
  double theta = std::acos(std::clamp(d.z, -1.0, 1.0));
  return {u < 1 ? u : 0.0, 1 - theta / kPi};
}

// The point's direction from the centre (the point alone: light sampling has no normal for it).
inline TexCoord texcoord_ref(const SphereTable& t, uint32_t i, const Surface& s) {
  return sphere_texcoord(normalize(s.p - glm::dvec3(t.center(i))));
}

}  // namespace raylane
