// Moving spheres: `mbsphere x0 y0 z0 x1 y1 z1 r`, a sphere whose centre moves linearly from
// (x0, y0, z0) when the shutter opens (time 0) to (x1, y1, z1) when it closes (time 1): motion
// blur (docs/motion-blur.md). The table, the kind's traits and its reference kernel; the SIMD
// kernel is in moving_sphere_packet.h.
#pragma once

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
#include "raylane/prims/solid.h"
#include "raylane/prims/sphere.h"
#include "raylane/prims/surface.h"
#include "raylane/prims/table_util.h"

namespace raylane {

// The centre at the opening (cx, cy, cz) and the motion over the shutter (mx, my, mz) = c1 − c0,
// rounded to float once, so that every kernel computes the centre at time t the same way:
// c0 + t·m. (The spec writes (1 − t)·c0 + t·c1, the same point; this form is exactly c0 when
// the ends are equal, so such a sphere is the static sphere at every time.)
struct MovingSphereTable {
  std::vector<float> cx, cy, cz, mx, my, mz, r;
  std::vector<uint32_t> material;

  auto columns() { return std::tie(cx, cy, cz, mx, my, mz, r, material); }
  std::size_t size() const { return r.size(); }
  glm::vec3 start(uint32_t i) const { return {cx[i], cy[i], cz[i]}; }
  glm::vec3 motion(uint32_t i) const { return {mx[i], my[i], mz[i]}; }
  // The centre at `time`, in double on the table's floats (the references' centre).
  glm::dvec3 center_at(uint32_t i, double time) const {
    return glm::dvec3(start(i)) + glm::dvec3(motion(i)) * time;
  }

  // p = (x0, y0, z0, x1, y1, z1, r); r must be > 0 after rounding to float, and both ends'
  // c ± r finite in float.
  std::optional<ParamError> append(std::span<const double, 7> p, uint32_t mat) {
    float radius = float(p[6]);
    if (!(radius > 0.0f))
      return ParamError{6, p[6] > 0 ? "mbsphere radius rounds to 0 in single precision; it must "
                                      "be > 0 after rounding (at least about 1.4e-45)"
                                    : "mbsphere radius must be > 0"};
    for (int k = 0; k < 6; ++k)  // both ends' bounds, centre ± radius, must be finite floats
      if (!std::isfinite(float(std::abs(p[k]) + double(radius))))
        return ParamError{k, "mbsphere reaches beyond float (the largest is about 3.4e38)"};
    // The motion between the ends as rounded to float: equal ends in the text move by exactly 0.
    auto motion = [&](int k) { return float(double(float(p[k + 3])) - double(float(p[k]))); };
    for (int k = 0; k < 3; ++k)  // the motion too (the ends can be finite and far apart)
      if (!std::isfinite(motion(k)))
        return ParamError{k + 3, "mbsphere moves beyond float (the largest is about 3.4e38)"};
    cx.push_back(float(p[0]));
    cy.push_back(float(p[1]));
    cz.push_back(float(p[2]));
    mx.push_back(motion(0));
    my.push_back(motion(1));
    mz.push_back(motion(2));
    r.push_back(radius);
    material.push_back(mat);
    return std::nullopt;
  }

  // The swept sphere's box: the union of the boxes of the sphere at the opening and at the
  // closing (a linear motion stays inside it at every time in between).
  Bounds3f bounds(uint32_t i) const {
    glm::dvec3 rr(r[i], r[i], r[i]);
    glm::dvec3 c0 = center_at(i, 0), c1 = center_at(i, 1);
    return round_out(Bounds3d(min(c0, c1) - rr, max(c0, c1) + rr));
  }
};

struct MovingSphere {
  using Table = MovingSphereTable;
  static constexpr std::string_view name = "mbsphere", plural = "mbspheres", keyword = "mbsphere";
  static constexpr int param_count = 7;
  static constexpr bool two_sided = false;
  // The sphere's kernel and the lerp of the centre: about the sphere's cost (sphere.h).
  static constexpr double sah_test_cost = 0.35;
  // Its hit records' surfaces come from surface_ref, one hit at a time: they need the ray's
  // time, which the double lanes of the static kinds do not carry. The render's columns take
  // theirs from float lanes, which read it (moving_sphere_packet.h).
  static constexpr bool surface_in_lanes = false;
  static constexpr bool surface_in_float_lanes = true;
  static constexpr bool float_surface_out_of_line = true;  // as Cylinder's
  // Emitters: the sphere's sampling (sphere.h) about the centre at the path's time, which
  // LightSampler passes (lights.cpp: a light that moves is sampled at the path's time). The
  // sample_area without a time, which the kinds' interface asks for, is the sphere at
  // mid-shutter, the time the ray-casting views show.
  static double area(const Table& t, uint32_t i) { return 4 * kPi * double(t.r[i]) * t.r[i]; }
  static AreaSample sample_area(const Table& t, uint32_t i, double u_part, double u1, double u2) {
    return sample_area(t, i, u_part, u1, u2, 0.5);
  }
  static AreaSample sample_area(const Table& t, uint32_t i, double, double u1, double u2,
                                double time) {
    return sample_sphere_area(t.center_at(i, time), t.r[i], u1, u2);
  }
  static std::optional<SubtendedSample> sample_subtended(const Table& t, uint32_t i,
                                                         const glm::dvec3& ref, double u1,
                                                         double u2, double time) {
    return sample_sphere_cone(t.center_at(i, time), t.r[i], ref, u1, u2);
  }
  static std::optional<double> subtended_solid_angle(const Table& t, uint32_t i,
                                                     const glm::dvec3& ref, double time) {
    return sphere_cone_solid_angle(t.center_at(i, time), t.r[i], ref);
  }
  // The course's `lit` view lights from an emitting sphere's centre: here at mid-shutter, the
  // time the ray-casting views render.
  static glm::dvec3 point_light(const Table& t, uint32_t i) { return t.center_at(i, 0.5); }
};

// The reference kernel, in double on the table's floats: the sphere's (sphere.h) about the
// centre at the ray's time.
inline double intersect_ref(const MovingSphereTable& s, uint32_t i, const Rayd& ray) {
  return intersect_sphere_ref(s.center_at(i, ray.time), s.r[i], ray);
}

// The hit point projected back onto the sphere at the ray's time (sphere_surface, sphere.h).
inline Surface surface_ref(const MovingSphereTable& s, uint32_t i, const Rayd& ray, double t) {
  const SphereSurface<glm::dvec3> x =
      sphere_surface<double>(s.center_at(i, ray.time), double(s.r[i]), ray.o, ray.d, t);
  return {x.p, x.n, x.n};
}

// The centre at `time` as the float kernels compute it, c0 + time·m (moving_sphere_packet.h),
// over the number type N and its 3-vector V3.
template <class N, class V3>
V3 moving_center(const V3& c0, const V3& m, const N& time) {
  return V3{c0.x + time * m.x, c0.y + time * m.y, c0.z + time * m.z};
}

// A bound on the error of sphere_surface's point about the float centre c = c0 + time·m, for
// the offset along its normal: the sphere's (sphere_point_bound) about that centre, plus the
// centre's own error — one roundoff of the product time·m and one of the sum, each in its
// component (the reference's centre is the same sum in double) — and, for the point's roundings
// e as a whole, the sagitta |e|²/2r they can add across the normal (the chord's rise; it counts
// where a sphere is only a few float ulps of its coordinates wide, as for cylinders).
template <class N, class V3>
V3 moving_sphere_point_bound(const SphereSurface<V3>& s, const V3& c, const V3& m, const N& time,
                             const N& r) {
  using K = Num<N>;
  const N own(kFloatUnitRoundoff * (1 + 0x1p-20));
  const V3 sphere = sphere_point_bound<N>(s.p, s.offset);
  auto one = [&](const N& bound_k, const N& ck, const N& mk) {
    return bound_k + (K::abs(time * mk) + K::abs(ck)) * own;
  };
  const V3 e{one(sphere.x, c.x, m.x), one(sphere.y, c.y, m.y), one(sphere.z, c.z, m.z)};
  const N across = (e.x * e.x + e.y * e.y + e.z * e.z) / (N(2.0) * r) * N(1 + 0x1p-20);
  return V3{K::abs(s.n.x) * across + e.x, K::abs(s.n.y) * across + e.y,
            K::abs(s.n.z) * across + e.z};
}

// The sphere's (u, v) (sphere.h) of the point's direction from the centre, which is the outward
// normal: the surface alone does not say the time, the normal does not need it (the texture
// moves with the sphere).
inline TexCoord texcoord_ref(const MovingSphereTable&, uint32_t, const Surface& s) {
  return sphere_texcoord(s.ng);
}

}  // namespace raylane
