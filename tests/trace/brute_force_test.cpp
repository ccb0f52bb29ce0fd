// The brute-force oracle: nearest over kinds, ties, intervals, invalid rays, and the
// reference leak test on a closed mesh (docs/hard-cases.md T1).
#include <gtest/gtest.h>

#include <random>

#include "raylane/trace/brute_force.h"
#include "support/random_scene.h"

namespace raylane {
namespace {

Scene mixed_row_scene() {
  Scene s;
  s.materials.push_back(Material{});
  s.table<Sphere>().append(std::array<double, 4>{0, 0, 10, 1}, 0);            // z 9..11
  s.table<Box>().append(std::array<double, 6>{-1, -1, 5, 2, 2, 1}, 0);        // z 5..6
  s.table<Cylinder>().append(std::array<double, 7>{0, 0, 7, 0, 0, 1, 1}, 0);  // z 7..8
  return s;
}

TEST(BruteForce, NearestOverEveryKind) {
  Scene s = mixed_row_scene();
  Hit h = closest_hit_ref(s, {{0, 0, 0}, {0, 0, 1}});
  ASSERT_TRUE(h.hit());
  EXPECT_EQ(h.prim, PrimRef(tag_of<Box>, 0));
  EXPECT_EQ(h.t, 5.0);
  EXPECT_TRUE(h.front_face);
  h = closest_hit_ref(s, {{0, 0, 6.5}, {0, 0, 1}});
  EXPECT_EQ(h.prim, PrimRef(tag_of<Cylinder>, 0));
  EXPECT_EQ(h.t, 0.5);
  h = closest_hit_ref(s, {{0, 0, 10}, {0, 0, -1}});  // inside the sphere: its exit
  EXPECT_EQ(h.prim, PrimRef(tag_of<Sphere>, 0));
  EXPECT_FALSE(h.front_face);
}

TEST(BruteForce, RespectsTheInterval) {
  Scene s = mixed_row_scene();
  EXPECT_FALSE(closest_hit_ref(s, {{0, 0, 0}, {0, 0, 1}, 0, 5}).hit());
  EXPECT_FALSE(any_hit_ref(s, {{0, 0, 0}, {0, 0, 1}, 0, 5}));
  EXPECT_TRUE(any_hit_ref(s, {{0, 0, 0}, {0, 0, 1}, 0, 5.01}));
  EXPECT_EQ(closest_hit_ref(s, {{0, 0, 0}, {0, 0, 1}, 6.5, 100}).prim,
            PrimRef(tag_of<Cylinder>, 0));
}

TEST(BruteForce, EqualDistanceGoesToTheLowerRef) {
  Scene s;
  s.materials.push_back(Material{});
  for (int i = 0; i < 3; ++i)
    s.table<Box>().append(std::array<double, 6>{-1, -1, 5, 2, 2, 1}, 0);
  s.table<Sphere>().append(std::array<double, 4>{0, 0, 6, 1}, 0);  // also entered at z = 5
  Hit h = closest_hit_ref(s, {{0, 0, 0}, {0, 0, 1}});
  EXPECT_EQ(h.prim, PrimRef(tag_of<Sphere>, 0));
}

// docs/hard-cases.md N1: invalid rays hit nothing and produce no NaN.
TEST(BruteForce, InvalidRaysHitNothing) {
  Scene s = mixed_row_scene();
  const double nan = std::nan(""), inf = INFINITY;
  for (Rayd r :
       {Rayd{{nan, 0, 0}, {0, 0, 1}}, Rayd{{0, 0, 0}, {0, inf, 1}}, Rayd{{0, 0, 0}, {0, 0, 0}},
        Rayd{{0, 0, 0}, {0, 0, 1}, 0, nan}, Rayd{{0, 0, 0}, {0, 0, 1}, 3, 2}}) {
    EXPECT_FALSE(closest_hit_ref(s, r).hit());
    EXPECT_FALSE(any_hit_ref(s, r));
  }
}

TEST(BruteForce, AnyHitAgreesWithClosestHit) {
  Scene s = testing::random_scene(21, 100, 5);
  for (const Rayd& r0 : testing::random_rays(22, 3000, 6)) {
    Rayd r = r0;
    r.tmax = 3;
    EXPECT_EQ(any_hit_ref(s, r), closest_hit_ref(s, r).hit());
  }
}

// T1: from inside a closed, shared-vertex mesh, random rays and rays aimed exactly at
// vertices and at points on edges all hit it (the reference is watertight), at offsets
// 0, 1e4 and 1e5.
TEST(BruteForce, NoRayEscapesAClosedMesh) {
  for (double off : {0.0, 1e4, 1e5}) {
    Scene s;
    glm::dvec3 c(off, off, -off);
    testing::add_closed_uv_sphere(s, 23, 12, 24, c);
    const auto& t = s.table<Triangle>();
    std::mt19937_64 rng(24);
    std::uniform_real_distribution<double> u(-0.25, 0.25), w(0, 1);
    int escapes = 0, rays = 0;
    for (int i = 0; i < 3000; ++i) {
      glm::vec3 o(c + glm::dvec3(u(rng), u(rng), u(rng)));
      uint32_t row = uint32_t(rng() % t.size());
      glm::dvec3 target{};
      if (i % 3 == 0)
        target = glm::dvec3(t.p1(row));
      else if (i % 3 == 1)
        target = glm::dvec3(
            glm::vec3(glm::dvec3(t.p1(row)) * (1 - w(rng)) + glm::dvec3(t.p2(row)) * w(rng)));
      else
        target = glm::dvec3(o) + glm::dvec3(u(rng), u(rng), u(rng));
      glm::dvec3 d(glm::vec3(target - glm::dvec3(o)));
      if (length_squared(d) == 0) continue;
      ++rays;
      escapes += !closest_hit_ref(s, {glm::dvec3(o), d}).hit();
    }
    EXPECT_EQ(escapes, 0) << "offset " << off << " of " << rays;
  }
}

}  // namespace
}  // namespace raylane
