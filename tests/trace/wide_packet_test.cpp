// The packet tracer's walks over the 8-wide tree (hybrid packets handing their last lanes to
// single rays, each wide child tested once) and the occlusion packets' far-child-first order:
// tests on scenes built so that the walk's order and counts are known.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "raylane/bvh/bvh.h"
#include "raylane/scene/parser.h"
#include "raylane/trace/simd_tracer.h"
#include "support/random_scene.h"

namespace raylane {
namespace {

using testing::random_rays;
using testing::random_scene;

// Both trees, so that either traversal can run.
const BvhConfig kWithWideNodes{.wide_nodes = true};

// Packets of mixed directions walk the 8-wide tree and hand their last few lanes to single rays
// over it (trace/wide_packet_traverse.h): the answers are those of the packets alone, on the
// tree without wide nodes, bit for bit, and the hand-over did happen.
TEST(SimdTracer, HybridPacketsAnswerAsPacketsAlone) {
  Scene s = random_scene(31, 400, 10);
  testing::add_closed_uv_sphere(s, 24, 16, 32, {2, -1, 3});
  Scene s_wide = s;
  Bvh binary = build_bvh_and_reorder(s), wide = build_bvh_and_reorder(s_wide, kWithWideNodes);
  RayStream stream = RayStream::from(random_rays(32, 6000, 12));
  for (Isa isa : supported_isas()) {
    SimdTracer tracer(isa, Traversal::kPackets);
    HitStream alone, hybrid;
    tracer.closest(s, binary, stream, alone);
    TraversalCounters c = tracer.trace_counted(s_wide, wide, stream, hybrid, /*any_hit=*/false);
    EXPECT_EQ(alone.prim, hybrid.prim) << isa_name(isa);
    EXPECT_EQ(alone.t, hybrid.t) << isa_name(isa);
    EXPECT_GT(c.single_rays, 1000u) << isa_name(isa);
    EXPECT_GE(c.single_node_tests, c.single_rays) << isa_name(isa);
    EXPECT_GT(std::count_if(hybrid.prim.begin(), hybrid.prim.end(),
                            [](uint32_t p) { return p != PrimRef::kInvalidBits; }),
              1000);
  }
}

// Packets of mixed directions walk the 8-wide tree (trace/wide_packet_traverse.h). Eight
// spheres, one in each octant about the origin, one per leaf, make a wide root whose eight
// children are those leaves. Rays from the origin, ray j toward the sphere of octant j mod 8,
// (not normalised), fill packets of mixed directions at every width: each packet tests the root's
// eight child boxes once (the binary walk would test 15: the root and seven pairs), enters one leaf
// per sphere its lanes aim at, and every ray hits its own sphere.
TEST(SimdTracer, MixedPacketsTestEachChildOfAWideNodeOnce) {
  std::string text = "camera 0 0 0 1\n";
  auto sign = [](int octant, int axis) { return (octant >> axis) & 1 ? -1.0 : 1.0; };
  for (int o = 0; o < 8; ++o)
    text += "sphere " + std::to_string(5 * sign(o, 0)) + " " + std::to_string(5 * sign(o, 1)) +
            " " + std::to_string(5 * sign(o, 2)) + " 1\n";
  Scene s = parse_scene(text, "octants.scn").scene;
  Bvh bvh = build_bvh_and_reorder(s, {.max_leaf = 1, .forced_leaf = 1, .wide_nodes = true});
  ASSERT_EQ(bvh.wide.nodes.size(), 1u);
  ASSERT_EQ(bvh.wide.nodes[0].arity, 8);
  std::vector<Rayd> rays;
  for (int j = 0; j < 16; ++j)
    rays.push_back({{0, 0, 0}, {sign(j % 8, 0), sign(j % 8, 1), sign(j % 8, 2)}});
  const auto& spheres = s.table<Sphere>();
  for (Isa isa : supported_isas()) {
    SimdTracer tracer(isa, Traversal::kPackets);
    HitStream hits;
    TraversalCounters c =
        tracer.trace_counted(s, bvh, RayStream::from(rays), hits, /*any_hit=*/false);
    const uint64_t width = uint64_t(tracer.width());
    EXPECT_EQ(c.packets, 16 / width) << isa_name(isa);
    EXPECT_EQ(c.node_tests, 8 * c.packets) << isa_name(isa);
    EXPECT_EQ(c.leaf_visits, c.packets * std::min<uint64_t>(width, 8)) << isa_name(isa);
    EXPECT_EQ(c.single_rays, 0u) << isa_name(isa);
    for (int j = 0; j < 16; ++j) {
      ASSERT_NE(hits.prim[j], PrimRef::kInvalidBits) << isa_name(isa) << " ray " << j;
      const uint32_t row = PrimRef::from_bits(hits.prim[j]).row();
      EXPECT_EQ(spheres.cx[row] * sign(j % 8, 0), 5.0f) << isa_name(isa) << " ray " << j;
      EXPECT_EQ(spheres.cy[row] * sign(j % 8, 1), 5.0f) << isa_name(isa) << " ray " << j;
      EXPECT_EQ(spheres.cz[row] * sign(j % 8, 2), 5.0f) << isa_name(isa) << " ray " << j;
      EXPECT_NEAR(hits.t[j], (std::sqrt(75.0) - 1.0) / std::sqrt(3.0), 1e-5)
          << isa_name(isa) << " ray " << j;
    }
  }
}

// Occlusion packets visit the farther child first (trace/packet_traverse.h, left_child_first).
// Shadow rays leave a grid of small triangles in z = 0 for a point light at z = 10, and one
// large triangle at z = 5 blocks every one of them. The root's children are the grid (near) and
// the blocker (far): far first, each packet tests the blocker's row, every lane is occluded, and
// the grid's leaves around the origins — which front-to-back order tests first, several rows
// per packet — are never tested. Coherent packets (the light beyond the grid's corner: every
// direction in one octant) and mixed ones (the light above its centre) take different paths.
TEST(SimdTracer, OcclusionPacketsVisitTheFartherChildFirst) {
  Scene s;
  s.materials.push_back(Material{});
  auto& tri = s.table<Triangle>();
  const glm::vec3 up(0, 0, 1);
  constexpr int kCells = 32;
  for (int i = 0; i < kCells; ++i)
    for (int j = 0; j < kCells; ++j) {
      float x0 = float(i) / kCells, x1 = float(i + 1) / kCells;
      float y0 = float(j) / kCells, y1 = float(j + 1) / kCells;
      tri.append({glm::vec3(x0, y0, 0), glm::vec3(x1, y0, 0), glm::vec3(x1, y1, 0)}, {up, up, up},
                 0);
      tri.append({glm::vec3(x0, y0, 0), glm::vec3(x1, y1, 0), glm::vec3(x0, y1, 0)}, {up, up, up},
                 0);
    }
  // Its box is centred on the grid's in x and y, so only z separates the two: z is the root's
  // split axis, along which coherent packets order the children.
  tri.append({glm::vec3(-19.5f, -19.5f, 5), glm::vec3(20.5f, -19.5f, 5), glm::vec3(0.5f, 20.5f, 5)},
             {up, up, up}, 0);
  Bvh bvh = build_bvh_and_reorder(s);
  ASSERT_EQ(bvh.nodes[0].axis, 2);
  ASSERT_EQ(bvh.nodes[bvh.nodes[0].index + 1].count, 1);  // the blocker, alone
  for (glm::dvec3 light : {glm::dvec3(5, 5, 10), glm::dvec3(0.5, 0.5, 10)}) {
    std::vector<Rayd> rays;
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 16; ++j) {
        glm::dvec3 o(glm::vec3(float(0.1 + 0.05 * i), float(0.1 + 0.05 * j), 0.0f));
        rays.push_back({o, light - o, 0.0, 1.0});  // from the grid to the light
      }
    RayStream stream = RayStream::from(rays);
    for (Isa isa : supported_isas()) {
      HitStream hits;
      TraversalCounters c =
          SimdTracer(isa, Traversal::kPackets).trace_counted(s, bvh, stream, hits, true);
      EXPECT_EQ(std::count(hits.prim.begin(), hits.prim.end(), 0u), 256) << isa_name(isa);
      EXPECT_EQ(c.leaf_visits, c.packets) << isa_name(isa) << ", light " << light.x;
      EXPECT_EQ(c.prim_tests, c.packets) << isa_name(isa) << ", light " << light.x;
    }
  }
}

// Single rays need the 8-wide tree; on a BVH built without it they go as packets, with the
// packets' answers, rather than missing everything.
TEST(SimdTracer, SingleRaysWithoutWideNodesGoAsPackets) {
  Scene s = random_scene(21, 200, 10);
  Bvh bvh = build_bvh_and_reorder(s);
  ASSERT_TRUE(bvh.wide.empty());
  RayStream stream = RayStream::from(random_rays(22, 3000, 12));
  HitStream packets, rays;
  SimdTracer(best_isa(), Traversal::kPackets).closest(s, bvh, stream, packets);
  SimdTracer(best_isa(), Traversal::kSingleRays).closest(s, bvh, stream, rays);
  EXPECT_EQ(packets.prim, rays.prim);
  EXPECT_EQ(packets.t, rays.t);
  EXPECT_GT(std::count_if(rays.prim.begin(), rays.prim.end(),
                          [](uint32_t p) { return p != PrimRef::kInvalidBits; }),
            300);
}

}  // namespace
}  // namespace raylane
