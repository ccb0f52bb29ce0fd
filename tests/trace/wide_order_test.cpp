// The children a ray enters at a wide node are visited nearest first, by the single-ray walk
// (trace/ray_traverse.h: sorted by entry distance) and by packets of mixed directions
// (trace/wide_packet_traverse.h: by the nearest entry among the lanes), in every direction
// octant: checked through the tracer's counters, as a ray that meets the nearest of eight
// entered leaves first finds its hit there and skips the other seven.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "raylane/bvh/bvh.h"
#include "raylane/scene/parser.h"
#include "raylane/trace/simd_tracer.h"

namespace raylane {
namespace {

double sign(int octant, int axis) {
  return (octant >> axis) & 1 ? -1.0 : 1.0;
}

// Eight unit spheres on the diagonal of `octant`, at 3, 6 … 24 times its sign vector, one per
// leaf: a wide root whose eight children a ray from the origin along the diagonal all enters.
// Listed farthest first, so that the build's slot order is not already the nearest first.
Scene spheres_on_diagonal(int octant) {
  std::string text = "camera 0 0 0 1\n";
  for (int k = 8; k >= 1; --k)
    text += "sphere " + std::to_string(3 * k * sign(octant, 0)) + " " +
            std::to_string(3 * k * sign(octant, 1)) + " " +
            std::to_string(3 * k * sign(octant, 2)) + " 1\n";
  return parse_scene(text, "diagonal.scn").scene;
}

TEST(WideOrder, SingleRaysVisitTheNearestChildFirstInEveryOctant) {
  for (int octant = 0; octant < 8; ++octant) {
    Scene s = spheres_on_diagonal(octant);
    Bvh bvh = build_bvh_and_reorder(s, {.max_leaf = 1, .forced_leaf = 1, .wide_nodes = true});
    ASSERT_EQ(bvh.wide.nodes.size(), 1u);
    ASSERT_EQ(bvh.wide.nodes[0].arity, 8);
    const std::vector<Rayd> rays = {
        {{0, 0, 0}, {sign(octant, 0), sign(octant, 1), sign(octant, 2)}}};
    for (Isa isa : supported_isas()) {
      SimdTracer tracer(isa, Traversal::kSingleRays);
      HitStream hits;
      TraversalCounters c = tracer.trace_counted(s, bvh, RayStream::from(rays), hits, false);
      EXPECT_EQ(c.leaf_visits, 1u) << isa_name(isa) << ", octant " << octant;
      EXPECT_NEAR(hits.t[0], (std::sqrt(27.0) - 1.0) / std::sqrt(3.0), 1e-5)
          << isa_name(isa) << ", octant " << octant;
    }
  }
}

// Packets whose lanes but one go along the diagonal (lane 0 has x reversed and meets nothing):
// mixed directions, so the wide walk; every other lane hits the nearest sphere.
TEST(WideOrder, MixedPacketsVisitTheNearestChildFirstInEveryOctant) {
  for (int octant = 0; octant < 8; ++octant) {
    Scene s = spheres_on_diagonal(octant);
    Bvh bvh = build_bvh_and_reorder(s, {.max_leaf = 1, .forced_leaf = 1, .wide_nodes = true});
    for (Isa isa : supported_isas()) {
      SimdTracer tracer(isa, Traversal::kPackets);
      const int width = tracer.width();
      std::vector<Rayd> rays;
      for (int j = 0; j < 2 * width; ++j) {
        const double flip = j % width == 0 ? -1.0 : 1.0;
        rays.push_back({{0, 0, 0}, {flip * sign(octant, 0), sign(octant, 1), sign(octant, 2)}});
      }
      HitStream hits;
      TraversalCounters c = tracer.trace_counted(s, bvh, RayStream::from(rays), hits, false);
      EXPECT_EQ(c.packets, 2u) << isa_name(isa);
      EXPECT_EQ(c.single_rays, 0u) << isa_name(isa) << ", octant " << octant;
      EXPECT_EQ(c.leaf_visits, c.packets) << isa_name(isa) << ", octant " << octant;
      for (int j = 0; j < 2 * width; ++j)
        EXPECT_EQ(hits.prim[j] == PrimRef::kInvalidBits, j % width == 0)
            << isa_name(isa) << ", octant " << octant << ", ray " << j;
    }
  }
}

}  // namespace
}  // namespace raylane
