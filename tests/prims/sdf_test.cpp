// The SDF reference marcher (sdf.h, sdf.cpp) on the hard cases of docs/scene-language.md, "SDF
// blocks": against analytic answers, an independent root finder, the CSG block of
// the same lines, grazing rays, rays from inside, far and tiny shapes, invalid rays.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "scene/scene_test_util.h"

namespace raylane {
namespace {

using testing::errors;

constexpr double kInf = std::numeric_limits<double>::infinity();

ParsedScene parsed(const std::string& body) {
  auto p = testing::parse(std::string(testing::kCameraLine) + "brdf 0.5 0.5 0.5 0 0 0 10\n" + body);
  EXPECT_TRUE(p.ok()) << (p.ok() ? "" : errors(p)[0]);
  return p;
}
SdfTable blocks(const std::string& body) {
  return parsed(body).scene.table<Sdf>();
}

Rayd ray(glm::dvec3 o, glm::dvec3 d, double tmin = 0, double tmax = kInf) {
  return {o, d, tmin, tmax};
}

double tolerance(const Rayd& r, double t) {
  double o = std::max({std::abs(r.o.x), std::abs(r.o.y), std::abs(r.o.z)});
  return sdf_tolerance(t * length(r.d), o);
}

// An independent root finder: the block's distance sampled along the ray at steps of `dt`
// (smaller than any feature of the shapes below), the first sign change bisected. No sphere
// tracing, no tolerance.
double first_crossing(const SdfTable& s, const Rayd& r, double dt, double tmax) {
  auto f = [&](double t) { return sdf_distance_ref(s, 0, r.at(t)); };
  double a = r.tmin, fa = f(a);
  for (double b = a + dt; b < tmax; a = b, b += dt) {
    double fb = f(b);
    if ((fa > 0) != (fb > 0)) {
      for (int i = 0; i < 60; ++i) {
        double m = 0.5 * (a + b);
        ((f(m) > 0) == (fa > 0) ? a : b) = m;
      }
      return a;
    }
    fa = fb;
  }
  return kInf;
}

TEST(SdfMath, SmoothOperatorsBlendByAQuarterOfK) {
  // Equal distances: h = 1, smin = a − k/4; far apart (|a − b| ≥ k): the sharp answer.
  EXPECT_DOUBLE_EQ(sdf_combine(kSdfSmoothUnion, 1.0, 1.0, 0.4), 0.9);
  EXPECT_DOUBLE_EQ(sdf_combine(kSdfSmoothUnion, 1.0, 2.0, 0.4), 1.0);
  EXPECT_DOUBLE_EQ(sdf_combine(kSdfSmoothIntersect, 1.0, 1.0, 0.4), 1.1);
  EXPECT_DOUBLE_EQ(sdf_combine(kSdfSmoothDifference, 1.0, -1.0, 0.4), 1.1);
  // Halfway: h = 1/2, smin = min − k/16.
  EXPECT_DOUBLE_EQ(sdf_combine(kSdfSmoothUnion, 1.0, 1.2, 0.4), 1.0 - 0.4 / 16);
  EXPECT_DOUBLE_EQ(sdf_combine(kSdfDifference, 1.0, -3.0, 0.0), 3.0);
}

TEST(SdfRef, ASphereIsHitWithinTheToleranceAndItsNormalIsRadial) {
  SdfTable s = blocks("sdf\nsphere 0 0 0 1\nend\n");
  Rayd r = ray({0, 0, 5}, {0, 0, -1});
  Sdf::LeafHit h = Sdf::hit_ref(s, 0, r);
  EXPECT_LE(h.t, 4.0);
  EXPECT_GE(h.t, 4.0 - tolerance(r, 4.0));
  Surface surf = surface_ref(s, h.row, r, h.t);
  EXPECT_NEAR(surf.ng.z, 1.0, 1e-9);
  EXPECT_NEAR(surf.p.z, 1.0, 1e-9);  // moved onto the surface along the normal
}

// Random rays at each exact leaf: depth against the sphere's analytic root and the independent
// root finder to 2e-3 relative wherever the ray meets the surface at cos > 0.1 (the error along
// the ray is the tolerance over the cosine: 1e-3 at most there); normals to 1e-2 of the
// gradient found by the root finder's point.
TEST(SdfRef, DepthAgreesWithAnIndependentRootFinder) {
  const char* shapes[] = {"sphere 0.1 0.2 0.3 1", "box -1 -0.5 -0.8 2 1 1.6",
                          "cylinder 0 -1 0 0.3 2 0.1 0.6", "torus 0 0 0 0.2 1 0.3 1 0.3"};
  std::mt19937_64 rng(51);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const char* shape : shapes) {
    SCOPED_TRACE(shape);
    SdfTable s = blocks(std::string("sdf\n") + shape + "\nend\n");
    int hits = 0;
    for (int i = 0; i < 400; ++i) {
      glm::dvec3 o = 4.0 * normalize(glm::dvec3(u(rng), u(rng), u(rng)));
      glm::dvec3 d = normalize(glm::dvec3(u(rng), u(rng), u(rng)) * 0.3 - o / 4.0);
      Rayd r = ray(o, d);
      double want = first_crossing(s, r, 1e-3, 10);
      Sdf::LeafHit h = Sdf::hit_ref(s, 0, r);
      if (want == kInf) continue;
      Surface surf = surface_ref(s, h.row, r, want);
      double cosine = std::abs(dot(surf.ng, d));
      if (cosine < 0.1) continue;  // silhouettes aside
      ++hits;
      ASSERT_LT(h.t, kInf) << i;
      EXPECT_NEAR(h.t, want, 2e-3 * want) << i;
      EXPECT_LE(want - h.t, tolerance(r, h.t) / cosine * 1.01 + 1e-12) << i;
      EXPECT_LT(length(surface_ref(s, h.row, r, h.t).ng - surf.ng), 1e-2) << i;
    }
    EXPECT_GT(hits, 100);
  }
}

// The same lines in a csg block and an sdf block are the same solid: depth within the
// tolerance over the cosine where both hit; a hit of one and a miss of the other only at a
// silhouette (the csg hit grazing, or the sdf hit's ray passing within the tolerance).
// Whether p is 1e-2 or more from all but one of the leaves of the block below, by their
// distances written out here.
bool apart_from_seams(const glm::dvec3& p) {
  glm::dvec3 q = abs(p) - glm::dvec3(0.7);
  double leaves[] = {
      length(p) - 1,
      length(max(q, glm::dvec3(0))) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0),
      std::max(std::sqrt(p.x * p.x + p.y * p.y) - 0.4, std::abs(p.z) - 2),
      length(p - glm::dvec3(0.8)) - 0.3};
  int near = 0;
  for (double d : leaves)
    near += std::abs(d) < 1e-2;
  return near <= 1;
}

TEST(SdfRef, SharpOperatorsAreTheCsgBlockOfTheSameLines) {
  const std::string body =
      "sphere 0 0 0 1\nbox -0.7 -0.7 -0.7 1.4 1.4 1.4\nintersect\n"
      "cylinder 0 0 -2 0 0 4 0.4\ndifference\nsphere 0.8 0.8 0.8 0.3\nunion\nend\n";
  ParsedScene p = parsed("csg\n" + body + "sdf\n" + body);
  const CsgTable& c = p.scene.table<Csg>();
  const SdfTable& s = p.scene.table<Sdf>();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int both = 0, silhouettes = 0;
  for (int i = 0; i < 2000; ++i) {
    glm::dvec3 o = 3.0 * normalize(glm::dvec3(u(rng), u(rng), u(rng)));
    Rayd r = ray(o, normalize(0.4 * glm::dvec3(u(rng), u(rng), u(rng)) - o / 3.0));
    Csg::LeafHit want = Csg::hit_ref(c, 0, r);
    Sdf::LeafHit h = Sdf::hit_ref(s, 0, r);
    if (want.t < kInf && h.t < kInf) {
      double cosine = std::abs(dot(surface_ref(c, want.row, r, want.t).ng, r.d));
      ++both;
      EXPECT_LE(want.t - h.t, tolerance(r, h.t) / std::max(cosine, 1e-3) * 1.01) << i;
      EXPECT_GE(want.t - h.t, -1e-9) << i;  // a march never passes the surface
      // The material is the leaf's whose surface it is: the same leaf as the csg's, away from
      // the seams where two leaves are nearly as near.
      if (cosine > 0.1 && apart_from_seams(r.at(want.t))) {
        EXPECT_EQ(h.row - s.leaf_begin[0], want.row) << i;
      }
    } else if (want.t < kInf) {
      double cosine = std::abs(dot(surface_ref(c, want.row, r, want.t).ng, r.d));
      EXPECT_LT(cosine, 0.05) << i;
      ++silhouettes;
    } else if (h.t < kInf) {
      double d = std::abs(sdf_distance_ref(s, 0, r.at(h.t)));
      EXPECT_LT(d, tolerance(r, h.t)) << i;
      ++silhouettes;
    }
  }
  EXPECT_GT(both, 300);
  EXPECT_LT(silhouettes, 20);
}

TEST(SdfRef, SmoothUnionWithATinyKIsTheUnion) {
  SdfTable s = blocks(
      "sdf\nsphere 0 0 0 1\nsphere 1 0 0 0.7\nunion\nend\n"
      "sdf\nsphere 0 0 0 1\nsphere 1 0 0 0.7\nsmoothunion 1e-6\nend\n");
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0;
  for (int i = 0; i < 500; ++i) {
    Rayd r = ray({u(rng), u(rng), 4}, {0.1 * u(rng), 0.1 * u(rng), -1});
    Sdf::LeafHit a = Sdf::hit_ref(s, 0, r), b = Sdf::hit_ref(s, 1, r);
    if (a.t == kInf || b.t == kInf) continue;  // silhouettes aside (few: checked below)
    ++hits;
    EXPECT_NEAR(a.t, b.t, 2 * tolerance(r, a.t) / 0.05) << i;
  }
  EXPECT_GT(hits, 150);
}

// The smooth union fills the neck between two spheres: a ray through the gap at the middle
// hits where the union would miss.
TEST(SdfRef, SmoothUnionFillsTheNeck) {
  SdfTable s = blocks(
      "sdf\nsphere -1 0 0 0.9\nsphere 1 0 0 0.9\nsmoothunion 0.8\nend\n"
      "sdf\nsphere -1 0 0 0.9\nsphere 1 0 0 0.9\nunion\nend\n");
  Rayd r = ray({0, 0, 4}, {0, 0, -1});
  EXPECT_LT(Sdf::hit_ref(s, 0, r).t, 4.0);
  EXPECT_EQ(Sdf::hit_ref(s, 1, r).t, kInf);
}

// Rays parallel to the torus's axis at radius ρ near the inner rim R − r: a hit iff ρ is in
// [R − r, R + r], at the tube's top; the step count stays bounded as ρ approaches the rim.
TEST(SdfRef, RaysGrazingTheTorusInnerRimEndInBoundedSteps) {
  SdfTable s = blocks("sdf\ntorus 0 0 0 0 0 1 1 0.25\nend\n");
  uint32_t most = 0;
  for (double delta : {-1e-2, -1e-3, -1e-4, -1e-6, 1e-6, 1e-4, 1e-3, 1e-2}) {
    double rho = 0.75 + delta;
    Rayd r = ray({rho, 0, 3}, {0, 0, -1});
    Sdf::LeafHit h = Sdf::hit_ref(s, 0, r);
    most = std::max(most, h.steps);
    if (delta < -1e-3) {
      EXPECT_EQ(h.t, kInf) << delta;
    }
    if (delta > 1e-3) {
      double want = 3 - std::sqrt(0.25 * 0.25 - (rho - 1) * (rho - 1));
      EXPECT_NEAR(h.t, want, 2e-3 * want) << delta;
    }
  }
  EXPECT_LT(most, 200u);
}

TEST(SdfRef, ARayFromInsideHitsWhereItLeaves) {
  SdfTable s = blocks("sdf\nsphere 0 0 0 1\nsphere 0.5 0 0 1\nsmoothunion 0.3\nend\n");
  Rayd r = ray({0.25, 0, 0}, {0, 1, 0});
  Sdf::LeafHit h = Sdf::hit_ref(s, 0, r);
  ASSERT_LT(h.t, kInf);
  EXPECT_LT(std::abs(sdf_distance_ref(s, 0, r.at(h.t))), tolerance(r, h.t));
  EXPECT_GT(dot(surface_ref(s, h.row, r, h.t).ng, r.d), 0);  // leaving
}

// A secondary ray from the surface does not re-hit it: outward a miss, inward the far side.
TEST(SdfRef, ARayLeavingTheSurfaceDoesNotReHitIt) {
  SdfTable s = blocks("sdf\nsphere 0 0 0 1\nend\n");
  Rayd in = ray({0, 0, 5}, {0, 0, -1});
  Surface surf = surface_ref(s, 0, in, Sdf::hit_ref(s, 0, in).t);
  EXPECT_EQ(Sdf::hit_ref(s, 0, ray(surf.p, normalize(glm::dvec3(0.3, 0, 1)))).t, kInf);
  Sdf::LeafHit through = Sdf::hit_ref(s, 0, ray(surf.p, {0, 0, -1}));
  EXPECT_NEAR(through.t, 2.0, tolerance(in, 2.0));
}

// The tolerance scales with the distance travelled and the coordinates: a sphere 1e4 from the
// origin and one of radius 1e-3, each seen from 4 radii away, are hit within it; normals radial.
TEST(SdfRef, FarAndTinyShapesAreHitWithinTheirTolerance) {
  for (double scale : {1e-3, 1.0}) {
    for (double far : {0.0, 1e4}) {
      SCOPED_TRACE(::testing::Message() << "scale " << scale << ", at " << far);
      glm::dvec3 c(far, far, far);
      SdfTable s = blocks("sdf\nsphere " + std::to_string(far) + " " + std::to_string(far) + " " +
                          std::to_string(far) + " " + std::to_string(scale) + "\nend\n");
      Rayd r = ray(c + glm::dvec3(0.3, 0.2, 5) * scale, normalize(glm::dvec3(-0.3, -0.2, -5)));
      double want = intersect_sphere_ref(c, scale, r);
      Sdf::LeafHit h = Sdf::hit_ref(s, 0, r);
      ASSERT_LT(h.t, kInf);
      EXPECT_LE(want - h.t, 1.5 * tolerance(r, h.t));
      EXPECT_GE(want - h.t, -1e-12 * (far + 1));
      glm::dvec3 n = normalize(r.at(want) - c);
      EXPECT_LT(length(surface_ref(s, h.row, r, h.t).ng - n), 1e-2);
    }
  }
}

TEST(SdfRef, InvalidRaysMissAndNothingIsNaN) {
  SdfTable s = blocks("sdf\ntorus 0 0 0 0 1 0 1 0.3\nsphere 0 0 0 0.5\nsmoothunion 0.2\nend\n");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Rayd invalid[] = {ray({0, 0, 5}, {0, 0, 0}),     ray({0, 0, 5}, {nan, 0, -1}),
                          ray({nan, 0, 5}, {0, 0, -1}),  ray({0, 0, kInf}, {0, 0, -1}),
                          ray({0, 0, 5}, {0, 0, -kInf}), ray({0, 0, 5}, {0, 0, -1}, nan)};
  for (const Rayd& r : invalid)
    EXPECT_EQ(Sdf::hit_ref(s, 0, r).t, kInf);
  // A point where the gradient is zero (the torus's centre, on its axis, inside the sphere):
  // the normal falls back to one against the ray, finite.
  Surface surf = surface_ref(s, 0, ray({0, 0, 5}, {0, 0, -1}), 5);
  EXPECT_TRUE(std::isfinite(surf.ng.x) && std::isfinite(surf.ng.y) && std::isfinite(surf.ng.z));
}

}  // namespace
}  // namespace raylane
