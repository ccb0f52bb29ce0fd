// The sphere's reference kernel (docs/hard-cases.md §2).
#include <gtest/gtest.h>

#include <random>

#include "prims/prim_test_util.h"

namespace raylane {
namespace {

using namespace testing;

TEST(SphereRef, AnalyticHitAndNormal) {
  SphereTable s = one_sphere(0, 0, 5, 1);
  Rayd r = ray({0, 0, 0}, {0, 0, 1});
  EXPECT_EQ(intersect_ref(s, 0, r), 4.0);
  Surface sf = surface_ref(s, 0, r, 4.0);
  EXPECT_EQ(sf.ng, glm::dvec3(0, 0, -1));
  EXPECT_EQ(sf.p, glm::dvec3(0, 0, 4));
  EXPECT_EQ(intersect_ref(s, 0, ray({0, 2, 0}, {0, 0, 1})), kInf);   // passes beside it
  EXPECT_EQ(intersect_ref(s, 0, ray({0, 0, 0}, {0, 0, -1})), kInf);  // behind the origin
}

TEST(SphereRef, RespectsTheRayInterval) {
  SphereTable s = one_sphere(0, 0, 5, 1);
  Rayd r = ray({0, 0, 0}, {0, 0, 1});
  r.tmax = 4.0;
  EXPECT_EQ(intersect_ref(s, 0, r), kInf);  // open interval
  r.tmax = kInf;
  r.tmin = 4.5;
  EXPECT_EQ(intersect_ref(s, 0, r), 6.0);  // the far side
}

// S5: from the centre, t = r/|d| for any direction length; b = ±0 must not give q = 0.
TEST(SphereRef, OriginInsideHitsTheExit) {
  SphereTable s = one_sphere(1, 2, 3, 2);
  for (double len : {1.0, 0.5, 3.0}) {
    EXPECT_DOUBLE_EQ(intersect_ref(s, 0, ray({1, 2, 3}, {0, len, 0})), 2 / len);
    EXPECT_DOUBLE_EQ(intersect_ref(s, 0, ray({1, 2, 3}, {-0.0, -len, 0})), 2 / len);
  }
  Rayd r = ray({1, 2, 3 + 1.998}, {0, 0, 1});  // 0.999 r off centre
  EXPECT_NEAR(intersect_ref(s, 0, r), 0.002, 1e-15);
  EXPECT_TRUE(surface_ref(s, 0, r, intersect_ref(s, 0, r)).ng.z > 0.999);
}

// S1: a unit sphere at distance D, rays at perpendicular distance h; compared with the same
// computation in long double. Error bound from docs/hard-cases.md S1, with double's u = 2^-53.
TEST(SphereRef, FarSmallSphereDoesNotCancel) {
  for (double D : {1e1, 1e3, 1e5, 1e7}) {
    for (double h : {0.5, 0.999}) {
      SphereTable s = one_sphere(0, 0, D, 1);
      double t = intersect_ref(s, 0, ray({0, h, 0}, {0, 0, 1}));
      long double exact = (long double)D - std::sqrt(1.0L - (long double)h * h);
      ASSERT_NE(t, kInf) << D << " " << h;
      EXPECT_LE(std::abs(t - double(exact)), 8 * 0x1p-53 * (D + 1)) << D << " " << h;
    }
  }
}

// S4: tangent rays near the silhouette: no NaN; outside the ambiguous band, the reference's
// answer matches the geometry.
TEST(SphereRef, GrazingRaysNeverGiveNaN) {
  SphereTable s = one_sphere(0, 0, 10, 1);
  for (int k = -100; k <= 100; ++k) {
    double h = 1 + k * 1e-7;
    double t = intersect_ref(s, 0, ray({0, h, 0}, {0, 0, 1}));
    EXPECT_FALSE(std::isnan(t));
    if (k < -5) {
      EXPECT_NE(t, kInf) << k;
    }
    if (k > 5) {
      EXPECT_EQ(t, kInf) << k;
    }
  }
}

TEST(SphereRef, NormalsAreUnitAndPointsOnTheSurface) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  SphereTable s = one_sphere(3, -2, 1e4, 7);
  for (int i = 0; i < 10000; ++i) {
    glm::dvec3 d = normalize(glm::dvec3(g(rng), g(rng), g(rng)) * 0.001 + glm::dvec3(3, -2, 1e4));
    Rayd r = ray({0, 0, 0}, d);
    double t = intersect_ref(s, 0, r);
    if (t == kInf) continue;
    Surface sf = surface_ref(s, 0, r, t);
    EXPECT_NEAR(length(sf.ng), 1.0, 4e-16);
    EXPECT_NEAR(length(sf.p - glm::dvec3(3, -2, 1e4)), 7.0, 1e-11);
  }
}

}  // namespace
}  // namespace raylane
