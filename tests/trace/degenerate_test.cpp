// Deeply degenerate geometry (docs/hard-cases.md, "B2. Flat boxes and axis-aligned geometry
// (zero-thickness BVH nodes)" and "B7. Large coordinates and the slab test"): everything at one
// point, 10^5 coincident triangles, coordinates near ±1e30. The BVH must build within its stack
// depth, and the packet tracer must answer every ray (no crash, no hang, no NaN) as the double
// reference does.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "raylane/bvh/bvh.h"
#include "raylane/trace/brute_force.h"
#include "raylane/trace/simd_tracer.h"
#include "support/random_scene.h"

namespace raylane {
namespace {

void add_triangle(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  glm::vec3 n(0, 0, 1);
  s.table<Triangle>().append({a, b, c}, {n, n, n}, 0);
}

void add_sphere(Scene& s, double x, double y, double z, double r) {
  std::array<double, 4> p{x, y, z, r};
  ASSERT_FALSE(s.table<Sphere>().append(p, 0).has_value());
}

// Rays from `eye` towards jittered points around `target`.
std::vector<Rayd> rays_towards(glm::dvec3 eye, glm::dvec3 target, double spread, int n) {
  std::vector<Rayd> rays;
  for (int i = 0; i < n; ++i) {
    glm::dvec3 jitter(spread * std::sin(i * 1.7), spread * std::cos(i * 2.3), 0);
    rays.push_back({eye, normalize(target + jitter - eye)});
  }
  return rays;
}

// Traces with the best ISA and checks every answer against the reference on the same float
// rays: the same hit/miss status, and t within a relative 1e-4 when both hit. Not `exact`:
// a miss, or a farther hit, may be a float overflow, but no hit may be nearer than the true
// closest one. Returns the number of rays whose answer differs.
int expect_agreement(const Scene& s, const Bvh& bvh, const std::vector<Rayd>& rays,
                     bool exact = true) {
  RayStream stream;
  stream.resize(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i)
    stream.set(i, ray_cast<float>(rays[i]));
  HitStream hits;
  SimdTracer().closest(s, bvh, stream, hits);
  int misses = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    Hit ref = closest_hit_ref(s, testing::round_to_float(rays[i]));
    bool hit = hits.prim[i] != PrimRef::kInvalidBits;
    EXPECT_FALSE(std::isnan(hits.t[i])) << "ray " << i;
    misses += hit != ref.hit() || (hit && std::abs(hits.t[i] - ref.t) > 1e-4 * ref.t);
    if (!exact) {  // a hit nearer than the true closest one would be false
      if (hit) {
        EXPECT_GE(hits.t[i], ref.t * (1 - 1e-4)) << "ray " << i;
      }
      continue;
    }
    EXPECT_EQ(hit, ref.hit()) << "ray " << i;
    if (hit) {
      EXPECT_NEAR(hits.t[i], ref.t, 1e-4 * std::max(1.0, ref.t)) << "ray " << i;
    }
  }
  return misses;
}

void expect_sane(const Bvh& bvh, std::size_t prims) {
  std::size_t in_leaves = 0;
  for (const BvhNode& n : bvh.nodes)
    in_leaves += n.count;  // 0 for inner nodes
  EXPECT_EQ(in_leaves, prims);
  EXPECT_LT(bvh.stats.depth, uint32_t(kBvhStackSize));
}

TEST(DegenerateGeometry, EveryPrimitiveAtOnePoint) {
  Scene s;
  for (int i = 0; i < 3000; ++i) {
    add_sphere(s, 1, 2, 3, 1e-3);
    add_triangle(s, {1, 2, 3}, {1, 2, 3}, {1, 2, 3});  // zero area: no surface to hit
  }
  Bvh bvh = build_bvh_and_reorder(s);
  expect_sane(bvh, 6000);
  expect_agreement(s, bvh, rays_towards({1, 2, 10}, {1, 2, 3}, 2e-3, 64));
}

TEST(DegenerateGeometry, HundredThousandCoincidentTriangles) {
  Scene s;
  for (int i = 0; i < 100000; ++i)
    add_triangle(s, {-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
  Bvh bvh = build_bvh_and_reorder(s);
  expect_sane(bvh, 100000);
  // The reference costs 10^5 tests per ray: a few rays suffice, half of them miss.
  expect_agreement(s, bvh, rays_towards({0, 0, 5}, {0, 0, 0}, 1.5, 16));
}

// A scatter of spheres and triangles around ±`scale`, and rays across it from the origin and
// from a far corner.
void huge_scene(Scene& s, std::vector<Rayd>& rays, double scale) {
  for (int i = 0; i < 200; ++i) {
    double sx = i % 2 ? scale : -scale, sy = i % 3 ? scale : -scale;
    add_sphere(s, sx, sy, scale * (i % 5 - 2), scale * 0.01 * (1 + i % 7));
    float fx = float(sx), fy = float(sy), fz = float(scale);
    add_triangle(s, {fx, fy, fz}, {-fx, fy, -fz}, {0, -fy, fz});
  }
  rays = rays_towards({0, 0, 0}, {scale, scale, 0}, 0.1 * scale, 32);
  auto more = rays_towards({-scale, 0, 0.1 * scale}, {scale, -scale, scale}, 0.1 * scale, 32);
  rays.insert(rays.end(), more.begin(), more.end());
}

TEST(DegenerateGeometry, LargeCoordinatesAgreeWithTheReference) {
  Scene s;
  std::vector<Rayd> rays;
  huge_scene(s, rays, 1e12);
  Bvh bvh = build_bvh_and_reorder(s);
  expect_sane(bvh, 400);
  expect_agreement(s, bvh, rays);
}

// Far out, the float triangle kernel overflows: its t numerator is cubic in the coordinates
// (Woop et al. 2013, section 3), so beyond about 7e12 ((FLT_MAX)^(1/3)) the tracer may miss
// what the double reference hits. What it must still do is finish, give no NaN, and report
// no hit nearer than the true one. The number of differing rays is printed for the record.
TEST(DegenerateGeometry, HugeCoordinatesFinishWithoutFalseHits) {
  Scene s;
  std::vector<Rayd> rays;
  huge_scene(s, rays, 1e30);
  Bvh bvh = build_bvh_and_reorder(s);
  expect_sane(bvh, 400);
  int misses = expect_agreement(s, bvh, rays, /*exact=*/false);
  std::printf("at 1e30: %d of %zu rays differ from the reference\n", misses, rays.size());
}

}  // namespace
}  // namespace raylane
