// SDF blocks in the packet tracer (sdf_packet.h) at every instruction set and traversal against
// the double reference (sdf.cpp) through the brute-force oracle, with partially filled packets
// and invalid rays among them; and secondary rays from their surfaces with the render's offsets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "raylane/bvh/bvh.h"
#include "raylane/core/ray_offset.h"
#include "raylane/scene/parser.h"
#include "raylane/trace/brute_force.h"
#include "raylane/trace/simd_tracer.h"
#include "raylane/trace/tracer.h"
#include "support/random_scene.h"

namespace raylane {
namespace {

using testing::round_to_float;

constexpr double kInf = std::numeric_limits<double>::infinity();
const BvhConfig kWithWideNodes{.wide_nodes = true};

// A torus, a smooth union of spheres, a carved box, side by side along x, and a sphere of its
// own kind overlapping the torus (a nearer hit of another kind must stand).
const char* kBlocks =
    "camera 0 0 20 0.5\n"
    "brdf 0.5 0.5 0.5 0 0 0 10\n"
    "sdf\ntorus 0 0 0 0.3 1 0.2 1.2 0.35\nend\n"
    "sdf\nsphere 3 0 0 0.8\nsphere 4 0.3 0 0.6\nsmoothunion 0.5\nsphere 3.5 1 0 0.4\n"
    "smoothunion 0.3\nend\n"
    "sdf\nbox 6 -1 -1 2 2 2\nsphere 7 0 0 1.25\nintersect\ncylinder 7 0 -2 0 0 4 0.5\n"
    "smoothdifference 0.2\nend\n"
    "sphere 1.2 0 0.3 0.3\n";

Scene sdf_scene() {
  auto p = parse_scene(kBlocks, "sdf.scn");
  EXPECT_TRUE(p.ok());
  return std::move(p.scene);
}

// Rays from around the scene aimed into it, some from inside, with invalid rays among them.
std::vector<Rayd> rays_at(const Scene& s, int n, uint32_t seed) {
  Bounds3f b = s.bounds();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Rayd> out;
  for (int i = 0; i < n; ++i) {
    glm::dvec3 target(b.lo.x + u(rng) * (b.hi.x - b.lo.x), b.lo.y + u(rng) * (b.hi.y - b.lo.y),
                      b.lo.z + u(rng) * (b.hi.z - b.lo.z));
    glm::dvec3 o = i % 5 == 0
                       ? target
                       : glm::dvec3(4, 0, 0) +
                             12.0 * normalize(glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
    glm::dvec3 d = i % 5 == 0 ? glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) : target - o;
    Rayd r{o, d, 0, kInf};
    if (i % 97 == 3) r.o.x = std::nan("");
    if (i % 89 == 4) r.d = {0, 0, 0};
    out.push_back(round_to_float(r));
  }
  return out;
}

struct SdfConfig {
  Isa isa;
  Traversal traversal;
};

class SdfPacketTest : public ::testing::TestWithParam<SdfConfig> {
 protected:
  void SetUp() override {
    if (!isa_supported(GetParam().isa))
      GTEST_SKIP() << "this CPU lacks " << isa_name(GetParam().isa);
  }
  SimdTracer tracer() const { return SimdTracer(GetParam().isa, GetParam().traversal); }
};

// The lanes march by the reference, so they name its leaf, and its t to the tolerance (the
// traversal hands the kernel its own float copy of each ray).
TEST_P(SdfPacketTest, ClosestHitsAreTheReferences) {
  Scene s = sdf_scene();
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  std::vector<Rayd> rays = rays_at(s, 3001, 3);  // the last packet partly filled
  HitStream hits;
  tracer().closest(s, bvh, RayStream::from(rays), hits);
  int sdf_hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    ASSERT_FALSE(std::isnan(hits.t[i])) << i;
    Hit ref = closest_hit_ref(s, rays[i]);
    bool hit = hits.prim[i] != PrimRef::kInvalidBits;
    ASSERT_EQ(hit, ref.hit() && ray_is_valid(rays[i])) << i;
    if (!hit) continue;
    sdf_hits += ref.prim.tag() == tag_of<Sdf>;
    EXPECT_EQ(to_string(PrimRef::from_bits(hits.prim[i])), to_string(ref.prim)) << i;
    const Rayd& r = rays[i];
    double o = std::max({std::abs(r.o.x), std::abs(r.o.y), std::abs(r.o.z)});
    EXPECT_NEAR(hits.t[i], ref.t, sdf_tolerance(ref.t * length(r.d), o) / length(r.d)) << i;
  }
  EXPECT_GT(sdf_hits, int(rays.size()) / 5);
}

TEST_P(SdfPacketTest, OcclusionIsTheReferences) {
  Scene s = sdf_scene();
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  std::vector<Rayd> rays = rays_at(s, 2001, 4);
  for (std::size_t i = 0; i < rays.size(); ++i)
    rays[i].tmax = i % 2 ? 14.0 : 9.0;
  HitStream hits;
  tracer().occluded(s, bvh, RayStream::from(rays), hits);
  int blocked = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    if (!ray_is_valid(rays[i])) continue;
    Hit ref = closest_hit_ref(s, rays[i]);
    if (ref.hit() && std::abs(ref.t - rays[i].tmax) < 1e-3 * ref.t) continue;  // at the end
    bool want = any_hit_ref(s, rays[i]);
    blocked += want;
    EXPECT_EQ(hits.prim[i] != PrimRef::kInvalidBits, want) << i;
  }
  EXPECT_GT(blocked, 300);
}

// Secondary rays from the blocks' surfaces with the render's offsets (core/ray_offset.h): one
// continuing into the solid must meet its boundary from inside (a front face or a miss would be
// a leak), one reflected off it must not meet a surface from inside (acne). Without moving the
// hit point onto the surface (sdf.cpp, surface_ref), 127 of 1171 leaked: the march stops up to
// its tolerance outside. Some still do where the point lies on a seam of a sharp operator (the
// gradient there mixes two leaves'): fewer than 1 in 50 is allowed, and left to be fixed.
TEST_P(SdfPacketTest, SecondaryRaysNeitherLeakNorReHitWithTheRenderOffsets) {
  Scene s = sdf_scene();
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  Tracer tracer(s, bvh, TracerBackend::kPacket, GetParam().isa);
  std::vector<Rayd> first = rays_at(s, 3000, 5), into, out;
  std::vector<Hit> hits;
  tracer.closest(first, hits);
  for (std::size_t i = 0; i < first.size(); ++i) {
    const Hit& h = hits[i];
    if (!h.hit() || h.prim.tag() != tag_of<Sdf> || !h.front_face) continue;
    glm::dvec3 err = hit_point_error(first[i], h.t), n = h.surface.ng, d = normalize(first[i].d);
    if (std::abs(dot(d, n)) < 0.1) continue;  // silhouettes aside: the march stops short there
    into.push_back({offset_ray_origin(h.surface.p, err, n, -n), d});
    out.push_back({offset_ray_origin(h.surface.p, err, n, n), d - 2 * dot(d, n) * n});
  }
  std::vector<Hit> in_hits, out_hits;
  tracer.closest(into, in_hits);
  tracer.closest(out, out_hits);
  int leaks = 0, acne = 0;
  for (const Hit& h : in_hits)
    leaks += !h.hit() || h.front_face;
  for (const Hit& h : out_hits)
    acne += h.hit() && !h.front_face;
  std::printf("[ offsets  ] %zu rays into the solids, %d leaking; %zu reflected, %d re-hitting\n",
              into.size(), leaks, out.size(), acne);
  EXPECT_GT(into.size(), 300u);
  EXPECT_LT(leaks, int(into.size()) / 50);
  EXPECT_EQ(acne, 0);
}

INSTANTIATE_TEST_SUITE_P(EveryIsa, SdfPacketTest,
                         ::testing::Values(SdfConfig{Isa::kSse42, Traversal::kPackets},
                                           SdfConfig{Isa::kAvx2, Traversal::kPackets},
                                           SdfConfig{Isa::kAvx512, Traversal::kPackets},
                                           SdfConfig{Isa::kSse42, Traversal::kSingleRays},
                                           SdfConfig{Isa::kAvx2, Traversal::kSingleRays},
                                           SdfConfig{Isa::kAvx512, Traversal::kSingleRays}),
                         [](const auto& info) {
                           std::string n(isa_name(info.param.isa));
                           n.erase(std::remove(n.begin(), n.end(), '.'), n.end());
                           return n + "_" + std::string(traversal_name(info.param.traversal));
                         });

}  // namespace
}  // namespace raylane
