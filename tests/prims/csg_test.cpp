// The CSG reference kernel (csg.h, csg.cpp) on the hard cases of docs/scene-language.md, "CSG
// blocks", and against an independent caster that classifies points along the ray.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "scene/scene_test_util.h"

namespace raylane {
namespace {

using testing::errors;

constexpr double kInf = std::numeric_limits<double>::infinity();

CsgTable blocks(const std::string& body) {
  auto p = testing::parse(std::string(testing::kCameraLine) + "brdf 0.5 0.5 0.5 0 0 0 10\n" + body);
  EXPECT_TRUE(p.ok()) << (p.ok() ? "" : errors(p)[0]);
  return p.scene.table<Csg>();
}

Rayd ray(glm::dvec3 o, glm::dvec3 d, double tmin = 0, double tmax = kInf) {
  return {o, d, tmin, tmax};
}

TEST(CsgRef, ALensIsWhereBothSpheresAre) {
  CsgTable c = blocks("csg\nsphere 0 0 -0.5 1\nsphere 0 0 0.5 1\nintersect\nend\n");
  Rayd r = ray({0, 0, 5}, {0, 0, -1});
  Csg::LeafHit h = Csg::hit_ref(c, 0, r);
  EXPECT_EQ(h.t, 4.5);  // z = 0.5: the first sphere's top
  EXPECT_EQ(h.row, 0u);
  Surface s = surface_ref(c, h.row, r, h.t);
  EXPECT_EQ(s.ng, glm::dvec3(0, 0, 1));
  // From below, the second sphere's bottom at z = -0.5.
  h = Csg::hit_ref(c, 0, ray({0, 0, -5}, {0, 0, 1}));
  EXPECT_EQ(h.t, 4.5);
  EXPECT_EQ(h.row, 1u);
  // Beside the lens (|x| > sqrt(0.75) at z = 0) but inside either sphere alone: a miss.
  EXPECT_EQ(Csg::hit_ref(c, 0, ray({0.9, 0, 5}, {0, 0, -1})).t, kInf);
}

// A transmissive lens works as any solid: a ray enters through one sphere's surface, facing it,
// and the ray refracted inside leaves through the other's, from inside.
TEST(CsgRef, ALensIsLeftThroughTheOtherSphere) {
  CsgTable c = blocks("csg\nsphere 0 0 -0.5 1\nsphere 0 0 0.5 1\nintersect\nend\n");
  Rayd in = ray({0, 0, 5}, {0, 0, -1});
  Csg::LeafHit h = Csg::hit_ref(c, 0, in);
  EXPECT_LT(dot(surface_ref(c, h.row, in, h.t).ng, in.d), 0);  // entering
  Rayd inside = ray(in.at(h.t), {0.1, 0, -1}, 1e-9);           // bent toward the axis
  Csg::LeafHit out = Csg::hit_ref(c, 0, inside);
  EXPECT_EQ(out.row, 1u);
  EXPECT_GT(dot(surface_ref(c, out.row, inside, out.t).ng, inside.d), 0);  // leaving
  EXPECT_NEAR(inside.at(out.t).z, -0.5, 0.01);
}

TEST(CsgRef, AMinusAIsEmpty) {
  CsgTable c = blocks(
      "csg\nsphere 0 0 0 1\nsphere 0 0 0 1\ndifference\nend\n"
      "csg\nbox 0 0 0 1 1 1\nbox 0 0 0 1 1 1\ndifference\nend\n");
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 2000; ++i) {
    Rayd r = ray({3 * u(rng), 3 * u(rng), 3 * u(rng)}, {u(rng), u(rng), u(rng)}, 0);
    EXPECT_EQ(Csg::hit_ref(c, 0, r).t, kInf);
    EXPECT_EQ(Csg::hit_ref(c, 1, r).t, kInf);
  }
}

TEST(CsgRef, TouchingBoxesHaveNoFaceBetweenThem) {
  CsgTable c = blocks("csg\nbox 0 0 0 1 1 1\nbox 1 0 0 1 1 1\nunion\nend\n");
  // Along the row of both: in at x = 0, out at x = 2, nothing at the shared face x = 1.
  EXPECT_EQ(Csg::hit_ref(c, 0, ray({-1, 0.5, 0.5}, {1, 0, 0})).t, 1.0);
  EXPECT_EQ(Csg::hit_ref(c, 0, ray({0.5, 0.5, 0.5}, {1, 0, 0})).t, 1.5);
  EXPECT_EQ(Csg::hit_ref(c, 0, ray({1, 0.5, 0.5}, {1, 0, 0})).t, 1.0);
  // Grazing views of the top face across the seam: every ray hits the top (z = 1) plane.
  for (int i = 0; i <= 200; ++i) {
    glm::dvec3 target(0.99 + (i + 0.5) * 1e-4, 0.5, 1);  // not exactly on the seam's edge
    glm::dvec3 o(-20, 0.5, 1.01);
    Rayd r = ray(o, target - o);
    Csg::LeafHit h = Csg::hit_ref(c, 0, r);
    ASSERT_LT(h.t, kInf) << i;
    // The slab's t carries three double roundings, the point two more: a few ulps of the
    // distance travelled (about 20), far below 1e-12.
    EXPECT_NEAR(r.at(h.t).z, 1.0, 1e-12) << i;
    EXPECT_EQ(surface_ref(c, h.row, r, h.t).ng, glm::dvec3(0, 0, 1)) << i;
  }
}

TEST(CsgRef, TheEarlierLeafIsSeenOnExactlySharedFaces) {
  CsgTable c = blocks(
      "csg\nbox 0 0 0 1 1 1\nbox 0 0 0 2 2 1\nunion\nend\n"
      "csg\nbox 0 0 0 2 2 1\nbox 0 0 0 1 1 1\nunion\nend\n"
      "csg\nbox 0 0 0 1 1 1\nbox 0 0 0 2 2 1\nintersect\nend\n");
  Rayd r = ray({0.5, 0.5, 3}, {0, 0, -1});
  Csg::LeafHit a = Csg::hit_ref(c, 0, r), b = Csg::hit_ref(c, 1, r), i = Csg::hit_ref(c, 2, r);
  EXPECT_EQ(a.t, 2.0);
  EXPECT_EQ(a.row, c.leaf_begin[0]);
  EXPECT_EQ(b.row, c.leaf_begin[1]);
  EXPECT_EQ(i.row, c.leaf_begin[2]);
}

TEST(CsgRef, TheLeafSeenIsOneThatBoundsTheSolid) {
  // (B ∩ C) ∪ A, B ∩ C empty: B's top coincides with A's, but only A's bounds the solid.
  CsgTable c = blocks(
      "csg\nbox 0 0 0 1 1 1\nbox 5 5 5 1 1 1\nintersect\nbox 0 0 0 2 2 1\nunion\n"
      "end\n");
  Csg::LeafHit h = Csg::hit_ref(c, 0, ray({0.5, 0.5, 3}, {0, 0, -1}));
  EXPECT_EQ(h.t, 2.0);
  EXPECT_EQ(h.row, 2u);
}

TEST(CsgRef, RaysStartingInsideLeaveThroughTheRightSurface) {
  // A shell: the outer sphere minus the inner one.
  CsgTable c = blocks("csg\nsphere 0 0 0 1\nsphere 0 0 0 0.5\ndifference\nend\n");
  Rayd up = ray({0, 0, 0.75}, {0, 0, 1}), down = ray({0, 0, 0.75}, {0, 0, -1});
  Csg::LeafHit h = Csg::hit_ref(c, 0, up);
  EXPECT_EQ(h.t, 0.25);
  EXPECT_EQ(h.row, 0u);
  h = Csg::hit_ref(c, 0, down);
  EXPECT_EQ(h.t, 0.25);
  EXPECT_EQ(h.row, 1u);
  // The hole's wall faces into the hole: the subtracted sphere's normal turned around.
  EXPECT_EQ(surface_ref(c, h.row, down, h.t).ng, glm::dvec3(0, 0, -1));
  // From the centre (in the hole, outside the solid): the wall, entered.
  h = Csg::hit_ref(c, 0, ray({0, 0, 0}, {1, 0, 0}));
  EXPECT_EQ(h.t, 0.5);
  EXPECT_EQ(surface_ref(c, h.row, ray({0, 0, 0}, {1, 0, 0}), h.t).ng, glm::dvec3(-1, 0, 0));
}

TEST(CsgRef, ATangentSphereLeafAddsNoBoundary) {
  // A box with a ball bitten out; the ray runs inside the box and touches the ball at one point.
  CsgTable c = blocks(
      "csg\nbox -2 -2 -2 4 4 4\nsphere 0 0 0 1\ndifference\nend\n"
      "csg\nsphere 0 0 0 1\nend\n");
  Csg::LeafHit h = Csg::hit_ref(c, 0, ray({-1.5, 1, 0}, {1, 0, 0}));
  EXPECT_EQ(h.t, 3.5);
  EXPECT_EQ(h.row, 0u);
  // A ray tangent to a sphere alone does not enter it: no boundary, no NaN.
  EXPECT_EQ(Csg::hit_ref(c, 1, ray({-5, 1, 0}, {1, 0, 0})).t, kInf);
}

TEST(CsgRef, ASubtractedLeafLargerThanALeavesNothing) {
  CsgTable c = blocks(
      "csg\nsphere 0 0 0 1\nsphere 0 0 0 2\ndifference\nend\n"
      "csg\nbox -1 -1 -1 2 2 2\nsphere 0 0 3 3\ndifference\nend\n");
  EXPECT_EQ(Csg::hit_ref(c, 0, ray({0, 0, 5}, {0, 0, -1})).t, kInf);
  // The big ball takes the box's top; the ray down the axis meets its surface at z = 0.
  Rayd r = ray({0, 0, 5}, {0, 0, -1});
  Csg::LeafHit h = Csg::hit_ref(c, 1, r);
  EXPECT_EQ(h.t, 5.0);
  EXPECT_EQ(h.row, c.leaf_begin[1] + 1);
  EXPECT_EQ(surface_ref(c, h.row, r, h.t).ng, glm::dvec3(0, 0, 1));
}

// An independent caster (Roth's classification by points, not by intervals): a point is in a
// leaf by its distance or coordinates, in the block by evaluating the program on those; the
// first change of the point's membership along the ray, found by stepping and then bisection,
// must be the reference's hit.
struct PointLeaf {
  bool sphere;
  glm::dvec3 a, b;  // centre and (r, -, -), or the box's corners
  bool contains(const glm::dvec3& p) const {
    if (sphere) return length(p - a) <= b.x;
    return p.x >= a.x && p.x <= b.x && p.y >= a.y && p.y <= b.y && p.z >= a.z && p.z <= b.z;
  }
};

// The program evaluated on a stack of its own (not csg_classify's bit stack).
bool inside(const std::vector<PointLeaf>& leaves, std::span<const uint32_t> program,
            const glm::dvec3& p) {
  std::vector<bool> stack;
  for (uint32_t code : program) {
    if (code < kCsgMaxLeaves) {
      stack.push_back(leaves[code].contains(p));
      continue;
    }
    bool b = stack.back();
    stack.pop_back();
    bool a = stack.back();
    stack.back() = code == kCsgUnion ? a || b : code == kCsgIntersect ? a && b : a && !b;
  }
  return stack.at(0);
}

TEST(CsgRef, ThirtyLeavesAgreeWithAPointCaster) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const char* ops[] = {"union", "intersect", "difference"};
  for (int block = 0; block < 20; ++block) {
    std::ostringstream text;
    std::vector<PointLeaf> leaves;
    // Exact decimals of the floats: the table adds a box's diagonal to its corner in double
    // before rounding, as the point caster does.
    text.precision(17);
    text << "csg\n";
    for (int i = 0; i < 30; ++i) {
      glm::dvec3 c(float(u(rng)), float(u(rng)), float(u(rng)));
      double r = float(0.2 + 0.5 * std::abs(u(rng)));
      if (i % 3 == 2) {
        text << "box " << c.x << ' ' << c.y << ' ' << c.z << ' ' << r << ' ' << r << ' ' << r
             << '\n';
        leaves.push_back({false, c, glm::dvec3(float(c.x + r), float(c.y + r), float(c.z + r))});
      } else {
        text << "sphere " << c.x << ' ' << c.y << ' ' << c.z << ' ' << r << '\n';
        leaves.push_back({true, c, {r, 0, 0}});
      }
      // Mostly unions so that the solid is not empty, the others mixed in.
      if (i > 0) text << ops[rng() % 5 < 3 ? 0 : 1 + rng() % 2] << '\n';
    }
    text << "end\n";
    CsgTable c = blocks(text.str());
    if (c.size() == 0) continue;  // an empty intersection
    auto program = c.program_of(0);
    for (int k = 0; k < 100; ++k) {
      glm::dvec3 o(3 * u(rng), 3 * u(rng), 3 * u(rng)), target(0.5 * u(rng), 0.5 * u(rng), 0);
      Rayd r = ray(o, normalize(target - o));
      double t_ref = Csg::hit_ref(c, 0, r).t;
      // Step 1e-3 along the ray from t = 0 until membership changes; bisect to 1e-12.
      bool start = inside(leaves, program, r.at(1e-9));
      double lo = 0, hi = kInf;
      for (double t = 1e-3; t < 10; t += 1e-3)
        if (inside(leaves, program, r.at(t)) != start) {
          lo = t - 1e-3, hi = t;
          break;
        }
      if (hi == kInf) {
        // No change found at this step: a miss, or a sliver thinner than a step.
        if (t_ref < kInf) {
          EXPECT_LT(t_ref, 10.0);
        }
        continue;
      }
      for (int it = 0; it < 60; ++it) {
        double mid = 0.5 * (lo + hi);
        (inside(leaves, program, r.at(mid)) != start ? hi : lo) = mid;
      }
      // The reference may find a sliver the steps skipped, never a later boundary.
      EXPECT_LE(t_ref, hi + 1e-9) << block << " " << k;

      if (t_ref >= lo) {
        EXPECT_NEAR(t_ref, hi, 1e-9) << block << " " << k;
      }
    }
  }
}

TEST(CsgRef, FlipsFollowTheDifferencesAboveALeaf) {
  // A − (B − C): B is subtracted once (flipped), C twice (not).
  CsgTable c = blocks(
      "csg\nbox 0 0 0 3 3 3\nbox 1 1 1 1 1 1\nsphere 1.5 1.5 1.5 0.1\ndifference\n"
      "difference\nend\n");
  EXPECT_EQ(c.leaf_flip, (std::vector<uint32_t>{0, 1, 0}));
}

}  // namespace
}  // namespace raylane
