// The box's reference kernel (docs/hard-cases.md §4).
#include <gtest/gtest.h>

#include "prims/prim_test_util.h"

namespace raylane {
namespace {

using namespace testing;

TEST(BoxRef, AnalyticHitsAndFaces) {
  BoxTable b = one_box({0, 0, 0}, {1, 1, 1});
  Rayd r = ray({0.5, 0.5, -1}, {0, 0, 1});
  EXPECT_EQ(intersect_ref(b, 0, r), 1.0);
  EXPECT_EQ(surface_ref(b, 0, r, 1.0).ng, glm::dvec3(0, 0, -1));
  Rayd inside = ray({0.5, 0.5, 0.5}, {0, 0, 1});
  EXPECT_EQ(intersect_ref(b, 0, inside), 0.5);  // from inside: the exit face
  EXPECT_EQ(surface_ref(b, 0, inside, 0.5).ng, glm::dvec3(0, 0, 1));
  EXPECT_EQ(intersect_ref(b, 0, ray({2, 0.5, -1}, {0, 0, 1})), kInf);
}

// B1: a negative diagonal is the same box, bit for bit.
TEST(BoxRef, NegativeDiagonalIsTheSameBox) {
  BoxTable a = one_box({1, 1, 1}, {-2, 3, 0.5});
  BoxTable b = one_box({-1, 1, 1}, {2, 3, 0.5});
  EXPECT_EQ(a.lo(0), b.lo(0));
  EXPECT_EQ(a.hi(0), b.hi(0));
  Rayd r = ray({-3, 2, 1.2}, normalize(glm::dvec3(1, 0.1, 0.05)));
  EXPECT_EQ(intersect_ref(a, 0, r), intersect_ref(b, 0, r));
}

// B3 and B4: ±0 components, origins in face planes, on edges and corners, all with the
// closed-box policy: the answer is a hit at t = 1, the same for +0 and −0.
TEST(BoxRef, DegenerateRaysHitTheClosedBox) {
  BoxTable b = one_box({0, 0, 0}, {1, 1, 1});
  int cases = 0;
  for (double x : {0.0, 0.5, 1.0})
    for (double y : {0.0, 0.5, 1.0})
      for (double sx : {0.0, -0.0})
        for (double sy : {0.0, -0.0}) {
          Rayd r = ray({x, y, -1}, {sx, sy, 1});
          double t = intersect_ref(b, 0, r);
          ASSERT_EQ(t, 1.0) << x << " " << y << " " << sx << " " << sy;
          Surface sf = surface_ref(b, 0, r, t);
          EXPECT_EQ(sf.ng, glm::dvec3(0, 0, -1));
          ++cases;
        }
  EXPECT_EQ(cases, 36);
  // Parallel and outside: a miss, never NaN.
  EXPECT_EQ(intersect_ref(b, 0, ray({2, 0.5, -1}, {-0.0, 0, 1})), kInf);
}

// B5: through a corner, all three near planes meet at t = 1; the normal is one unit axis,
// the lowest of the tied axes.
TEST(BoxRef, CornerHitHasOneAxisNormal) {
  BoxTable b = one_box({0, 0, 0}, {1, 1, 1});
  Rayd r = ray({-1, -1, -1}, {1, 1, 1});
  double t = intersect_ref(b, 0, r);
  ASSERT_EQ(t, 1.0);
  EXPECT_EQ(surface_ref(b, 0, r, t).ng, glm::dvec3(-1, 0, 0));
}

// The packet kernels report t in float: the face must follow the nearer end of the
// interval, not an exact match with the double entry t (a float t once flipped the face).
TEST(BoxRef, SurfaceFromAnInexactTIsStillTheEntryFace) {
  BoxTable b = one_box({0, 0, 0}, {1, 1, 1});
  Rayd r = ray({0.3, 0.4, -1}, normalize(glm::dvec3(0.1, 0.2, 1)));
  double t = intersect_ref(b, 0, r);
  for (double tt : {t, double(float(t)), std::nextafter(t, 0.0), std::nextafter(t, 9.0)}) {
    Surface s = surface_ref(b, 0, r, tt);
    EXPECT_EQ(s.ng, glm::dvec3(0, 0, -1));
    EXPECT_EQ(s.p.z, 0.0);
  }
}

TEST(BoxRef, LargeOffsetsStayExact) {
  for (double off : {1e2, 1e4, 1e5, 1e6}) {
    BoxTable b = one_box({off, off, off}, {1, 1, 1});
    EXPECT_EQ(intersect_ref(b, 0, ray({off + 0.5, off + 0.5, off - 1}, {0, 0, 1})), 1.0) << off;
  }
}

}  // namespace
}  // namespace raylane
