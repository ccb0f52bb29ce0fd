// The capped cylinder's reference kernel (docs/hard-cases.md §3): base (0,0,0), axis (0,0,2),
// r = 1 unless stated, also turned to a generic axis and moved far away.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "prims/prim_test_util.h"

namespace raylane {
namespace {

using namespace testing;

TEST(CylinderRef, SideHitFromOutsideAndInside) {
  CylinderTable c = one_cylinder({0, 0, 0}, {0, 0, 2}, 1);
  Rayd r = ray({-3, 0, 1}, {1, 0, 0});  // C4: perpendicular to the axis
  EXPECT_EQ(intersect_ref(c, 0, r), 2.0);
  EXPECT_EQ(surface_ref(c, 0, r, 2.0).ng, glm::dvec3(-1, 0, 0));
  Rayd in = ray({0, 0, 1}, {0, 1, 0});
  EXPECT_EQ(intersect_ref(c, 0, in), 1.0);
  EXPECT_EQ(surface_ref(c, 0, in, 1.0).ng, glm::dvec3(0, 1, 0));
}

// C1: parallel to the axis, inside: the bottom cap at exactly t = 1, normal −axis.
TEST(CylinderRef, ParallelInsideHitsTheCap) {
  CylinderTable c = one_cylinder({0, 0, 0}, {0, 0, 2}, 1);
  Rayd r = ray({0.3, 0.2, -1}, {0, 0, 1});
  EXPECT_EQ(intersect_ref(c, 0, r), 1.0);
  EXPECT_EQ(surface_ref(c, 0, r, 1.0).ng, glm::dvec3(0, 0, -1));
  Rayd from_inside = ray({0.3, 0.2, 1}, {0, 0, 1});
  EXPECT_EQ(intersect_ref(c, 0, from_inside), 1.0);
  EXPECT_EQ(surface_ref(c, 0, from_inside, 1.0).ng, glm::dvec3(0, 0, 1));
}

// C2: parallel outside misses; parallel exactly on the surface is deterministic (inclusive:
// the bottom rim at t = 1).
TEST(CylinderRef, ParallelOutsideAndOnTheSurface) {
  CylinderTable c = one_cylinder({0, 0, 0}, {0, 0, 2}, 1);
  EXPECT_EQ(intersect_ref(c, 0, ray({1.5, 0, -1}, {0, 0, 1})), kInf);
  EXPECT_EQ(intersect_ref(c, 0, ray({1, 0, -1}, {0, 0, 1})), 1.0);
  EXPECT_EQ(intersect_ref(c, 0, ray({1, 0, -1}, {-0.0, 0, 1})), 1.0);
}

// C3: through the rim: a hit at t = 2.
TEST(CylinderRef, RimIsHit) {
  CylinderTable c = one_cylinder({0, 0, 0}, {0, 0, 2}, 1);
  EXPECT_DOUBLE_EQ(intersect_ref(c, 0, ray({3, 0, 4}, {-1, 0, -1})), 2.0);
}

// C4: a ray lying in a cap plane: closed solid, the rim at t = 2; no NaN for ±0.
TEST(CylinderRef, RayInACapPlane) {
  CylinderTable c = one_cylinder({0, 0, 0}, {0, 0, 2}, 1);
  for (double z : {0.0, 2.0})
    for (double zero : {0.0, -0.0})
      EXPECT_EQ(intersect_ref(c, 0, ray({-3, 0, z}, {1, 0, zero})), 2.0);
}

// A generic axis, far away: rays aimed at random points inside hit within the S1-style
// bound, and the hit point lies on the surface.
TEST(CylinderRef, GenericAxisFarAway) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1), s(0.05, 0.95);
  for (double off : {0.0, 1e4, 1e5}) {
    glm::dvec3 base(off, -off, off), axis = glm::dvec3(1, 2, 3);
    CylinderTable c = one_cylinder(base, axis, 0.5);
    glm::dvec3 b(c.base(0)), a(c.axis(0));
    glm::dvec3 ua = normalize(a);
    glm::dvec3 e1 = normalize(cross(ua, glm::dvec3(1, 0, 0))), e2 = cross(ua, e1);
    for (int i = 0; i < 2000; ++i) {
      glm::dvec3 target = b + a * s(rng) + (e1 * u(rng) + e2 * u(rng)) * (0.35 * 0.5);
      glm::dvec3 o = target + glm::dvec3(u(rng), u(rng), u(rng)) * 10.0;
      Rayd r = ray(o, normalize(target - o));
      double t = intersect_ref(c, 0, r);
      ASSERT_NE(t, kInf) << off << " " << i;
      glm::dvec3 p = r.at(t) - b;
      double z = dot(p, ua);
      double radial = length(p - z * ua);
      double tol = 64 * 0x1p-53 * (length(o) + 10);
      bool on_side = std::abs(radial - 0.5) <= tol && z >= -tol && z <= length(a) + tol;
      bool on_cap = radial <= 0.5 + tol && (std::abs(z) <= tol || std::abs(z - length(a)) <= tol);
      EXPECT_TRUE(on_side || on_cap) << off << " " << radial << " " << z;
    }
  }
}

// C5: thin and far: r = 1e-3 at distance 1e3, rays at 0.5 r from the axis.
TEST(CylinderRef, ThinFarCylinderIsHit) {
  CylinderTable c = one_cylinder({1000, 0, -5}, {0, 0, 10}, 1e-3);
  Rayd r = ray({0, 0.5e-3, 0}, {1, 0, 0});
  double t = intersect_ref(c, 0, r);
  double r_f = c.r[0];  // the stored (float) radius is the geometry
  double exact = 1000 - std::sqrt(r_f * r_f - 0.25e-6);
  EXPECT_NEAR(t, exact, 8 * 0x1p-53 * 1001);
}

// The table keeps no axis of its own: the axis is the rounded unit axis times the rounded
// height, exact in double, so it points along u and is h long to the last bit of h·|u|.
TEST(CylinderTable, AxisIsTheStoredUnitAxisTimesTheStoredHeight) {
  CylinderTable c = one_cylinder({1, 2, 3}, {0.3, -1.7, 2.9}, 0.25);
  glm::dvec3 a = c.axis(0), u(c.unit_axis(0));
  double h = c.h[0];
  EXPECT_EQ(a.x, u.x * h);
  EXPECT_EQ(a.y, u.y * h);
  EXPECT_EQ(a.z, u.z * h);
  // Within the rounding of u and h (a few ulps) of the given axis.
  glm::dvec3 given(0.3f, -1.7f, 2.9f);
  EXPECT_LE(length(a - given), 4 * 0x1p-24 * length(given));
}

// An axis whose float components are finite but whose length is not: |a| overflows the float
// height, so the row is refused rather than given h = inf (and an axis of inf and NaN).
TEST(CylinderTable, AxisLongerThanTheLargestFloatIsRefused) {
  CylinderTable c;
  std::array<double, 7> p{0, 0, 0, 3e38, 3e38, 0, 1};
  auto err = c.append(p, 0);
  ASSERT_TRUE(err.has_value());
  EXPECT_EQ(err->param, 3);
  EXPECT_EQ(c.size(), 0u);
  std::array<double, 7> ok{0, 0, 0, 2e38, 0, 0, 1};
  EXPECT_FALSE(c.append(ok, 0).has_value());
}

// How far p lies off the part of cylinder i that the normal n names, in double: a cap's plane or
// the side's round (the reference's cylinder: base b, axis u·h in double).
double off_its_part(const CylinderTable& c, uint32_t i, const glm::dvec3& p, const glm::dvec3& n) {
  const glm::dvec3 axis = c.axis(i), u = normalize(axis), q = p - glm::dvec3(c.base(i));
  const double h = length(axis), z = dot(q, u), along = dot(n, u);
  if (std::abs(along) > 0.5) return along < 0 ? std::abs(z) : std::abs(z - h);
  return std::abs(length(q - z * u) - double(c.r[i]));
}

// cylinder_surface's float point lies within cylinder_point_bound's projection on its normal of
// the part it is on, for random cylinders (a third of them along z) and rays through them: near
// the origin, 1e3 and 1e5 away, a thousand times thinner (a hundred float ulps of their
// coordinates wide), and at 1e5 about one ulp wide. The scalar float instance is the lanes' bit
// for bit (tests/trace/surface_columns_test.cpp). Planted mistakes: without the axial residual
// and the tilt (γ8 of the spread), 14 points lie beyond the bound, near the origin; without the
// sagitta |e|²/2r, 1 of the cylinders one ulp wide.
TEST(CylinderSurface, FloatPointLiesWithinItsBound) {
  struct Case {
    double scale, thin;
  };
  for (const Case& k : {Case{1, 1}, Case{1e3, 1}, Case{1e5, 1}, Case{1, 1e3}, Case{1e5, 30}}) {
    SCOPED_TRACE("scale " + std::to_string(k.scale) + ", thinner by " + std::to_string(k.thin));
    std::mt19937_64 g(1);
    std::uniform_real_distribution<double> U(-1, 1);
    int points = 0, beyond = 0, caps = 0;
    for (int n = 0; n < 2000; ++n) {
      const glm::dvec3 at(k.scale * U(g), k.scale * U(g), k.scale * U(g));
      const double len = 0.2 + std::abs(U(g));
      glm::dvec3 axis(len * U(g), len * U(g), len * U(g));
      if (n % 3 == 0) axis.x = axis.y = 0;
      const CylinderTable c = one_cylinder(at, axis, (0.02 + 0.3 * std::abs(U(g))) / k.thin);
      if (c.size() == 0) continue;
      for (int j = 0; j < 50; ++j) {
        const glm::dvec3 from = at + 3.0 * glm::dvec3(U(g), U(g), U(g));
        const glm::dvec3 to = glm::dvec3(c.base(0)) + c.axis(0) * (0.5 + 0.6 * U(g)) +
                              double(c.r[0]) * glm::dvec3(U(g), U(g), U(g));
        const glm::vec3 o(from), d(to - from);
        const double t = intersect_ref(c, 0, Rayd{glm::dvec3(o), glm::dvec3(d)});
        if (!std::isfinite(t)) continue;
        const glm::vec3 u = c.unit_axis(0);
        const CylinderSurface<float, glm::vec3> s =
            cylinder_surface<float>(c.base(0), u, c.h[0], c.r[0], o, d, float(t));
        const glm::dvec3 bound(cylinder_point_bound<float>(s, u, c.r[0])), nd(s.n);
        ++points, caps += bool(s.cap);
        beyond += !(off_its_part(c, 0, glm::dvec3(s.p), nd) <= dot(abs(nd), bound));
      }
    }
    EXPECT_EQ(beyond, 0);
    EXPECT_GT(points, 70000);
    EXPECT_GT(caps, k.thin > 1 ? 50 : 5000);  // a thin cylinder's caps are small
  }
}

}  // namespace
}  // namespace raylane
