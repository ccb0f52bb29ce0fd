// The packet tracer at every instruction set this CPU has, against the double-precision
// brute-force oracle, on the same float rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <random>
#include <set>
#include <string>

#include "raylane/bvh/bvh.h"
#include "raylane/scene/parser.h"
#include "raylane/trace/brute_force.h"
#include "raylane/trace/simd_tracer.h"
#include "support/error_bands.h"
#include "support/paths.h"
#include "support/random_scene.h"

namespace raylane {
namespace {

using testing::random_rays;
using testing::random_scene;
using testing::round_to_float;

// Both trees, so that either traversal can run.
const BvhConfig kWithWideNodes{.wide_nodes = true};

// Disagreements with the reference, sorted by docs/hard-cases.md §0's classes
// (support/error_bands): outside the band the kernel must give the reference's answer — the same
// primitive, t within the error bound — and inside it either answer is allowed, and counted. The
// reference runs on the float rays, converted exactly.
struct Agreement {
  int rays = 0, hits = 0, band = 0, band_disagreements = 0, disagreements_outside_band = 0;
};

Agreement compare(const Scene& s, const Bvh& bvh, const SimdTracer& tracer,
                  const std::vector<Rayd>& rays) {
  RayStream stream = RayStream::from(rays);
  HitStream hits;
  tracer.closest(s, bvh, stream, hits);
  Agreement a;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    Rayd ray = round_to_float(rays[i]);
    Hit ref = closest_hit_ref(s, ray);
    testing::RayVerdict v = testing::classify_closest(s, ray, /*skip_far_bounds=*/true);
    ++a.rays;
    bool hit = hits.prim[i] != PrimRef::kInvalidBits;
    EXPECT_FALSE(std::isnan(hits.t[i]));
    if (ref.hit()) ++a.hits;
    bool same = hit == ref.hit() && (!hit || hits.prim[i] == ref.prim.bits());
    if (v.cls == testing::RayClass::kBand) {
      ++a.band;
      a.band_disagreements += !same;
    } else {
      bool t_ok = v.cls != testing::RayClass::kClearHit || std::abs(hits.t[i] - v.t) <= v.t_bound;
      a.disagreements_outside_band += !same || !t_ok;
    }
  }
  return a;
}

// Every instruction set with both traversals: packets over the binary tree, single rays
// over the 8-wide tree.
struct TracerConfig {
  Isa isa;
  Traversal traversal;
};

class SimdTracerTest : public ::testing::TestWithParam<TracerConfig> {
 protected:
  void SetUp() override {
    if (!isa_supported(GetParam().isa))
      GTEST_SKIP() << "this CPU lacks " << isa_name(GetParam().isa);
  }
  SimdTracer tracer() const { return SimdTracer(GetParam().isa, GetParam().traversal); }
  bool packets() const { return GetParam().traversal == Traversal::kPackets; }
};

TEST_P(SimdTracerTest, AgreesWithReferenceOnRandomScenes) {
  for (double offset : {0.0, 1e2, 1e4}) {
    Scene s = random_scene(11, 300, 10, 0.6, {offset, offset, -offset});
    Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
    // 10001 rays: the last packet is partly filled.
    Agreement a = compare(s, bvh, tracer(), random_rays(12, 10001, 12, {offset, offset, -offset}));
    EXPECT_GT(a.hits, a.rays / 10);
    EXPECT_EQ(a.disagreements_outside_band, 0) << "offset " << offset;
    std::printf("[ bands    ] offset %g: %d rays, %d in the band, %d of them disagreeing\n", offset,
                a.rays, a.band, a.band_disagreements);
  }
}

TEST_P(SimdTracerTest, AgreesWithReferenceOnShippedScenes) {
  for (const char* name : {"testscene", "sphere", "box", "cylinder", "mesh"}) {
    auto p = load_scene_file(testing::source_path(std::string("scenes/") + name + ".scn"));
    ASSERT_TRUE(p.ok());
    Bvh bvh = build_bvh_and_reorder(p.scene, kWithWideNodes);
    // 10^5 rays per scene at every ISA: the shipped scenes' agreement check, as
    // docs/hard-cases.md, "How raylane implements it: error bands", sets it.
    Agreement a = compare(p.scene, bvh, tracer(), random_rays(13, 100000, 3));
    EXPECT_EQ(a.disagreements_outside_band, 0) << name;
    EXPECT_GT(a.hits, 0) << name;
    std::printf("[ bands    ] %s: %d rays, %d in the band, %d of them disagreeing\n", name, a.rays,
                a.band, a.band_disagreements);
  }
}

// docs/hard-cases.md N1: invalid rays miss without a NaN, and do not disturb their packet mates.
TEST_P(SimdTracerTest, InvalidRaysMissAndLeaveOtherLanesAlone) {
  Scene s = random_scene(14, 50, 3);
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  std::vector<Rayd> rays = random_rays(15, 64, 3);
  const double nan = std::nan(""), inf = INFINITY;
  rays[1].o.x = nan;
  rays[2].d.y = inf;
  rays[3].d = {0, 0, 0};
  rays[4].tmax = nan;
  rays[5].tmin = 2, rays[5].tmax = 1;
  rays[6].o.z = 1e39;  // inf after rounding to float
  RayStream stream = RayStream::from(rays);
  HitStream hits;
  tracer().closest(s, bvh, stream, hits);
  for (int i = 1; i <= 6; ++i) {
    EXPECT_EQ(hits.prim[i], PrimRef::kInvalidBits) << i;
    EXPECT_FALSE(std::isnan(hits.t[i])) << i;
  }
  for (int i = 7; i < 64; ++i) {
    Hit ref = closest_hit_ref(s, round_to_float(rays[i]));
    EXPECT_EQ(hits.prim[i] != PrimRef::kInvalidBits, ref.hit()) << i;
  }
}

// docs/hard-cases.md B3, B4: ±0 components and rays in a box's face planes, edges and corners.
TEST_P(SimdTracerTest, BoxFacePlaneAndSignedZeroRays) {
  Scene s;
  s.materials.push_back(Material{});
  s.table<Box>().append(std::array<double, 6>{0, 0, 0, 1, 1, 1}, 0);
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  std::vector<Rayd> rays;
  for (double x : {0.0, 0.5, 1.0})
    for (double y : {0.0, 0.5, 1.0})
      for (double zx : {0.0, -0.0})
        for (double zy : {0.0, -0.0})
          rays.push_back({{x, y, -1}, {zx, zy, 1}});
  RayStream stream = RayStream::from(rays);
  HitStream hits;
  tracer().closest(s, bvh, stream, hits);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    Hit ref = closest_hit_ref(s, rays[i]);
    ASSERT_TRUE(ref.hit()) << i;  // closed box: face, edge and corner rays hit
    EXPECT_EQ(hits.prim[i], ref.prim.bits()) << i;
    EXPECT_EQ(hits.t[i], 1.0f) << i;
  }
}

// docs/hard-cases.md T1: rays from inside a closed mesh, random and aimed exactly at vertices and
// at points on edges, through the BVH, at offsets 0, 1e4 and 1e5: no ray escapes.
TEST_P(SimdTracerTest, NoRayEscapesAClosedMesh) {
  for (double offset : {0.0, 1e4, 1e5}) {
    Scene s;
    glm::dvec3 c(offset, -offset, offset);
    testing::add_closed_uv_sphere(s, 16, 24, 48, c);
    Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
    const auto& t = s.table<Triangle>();
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(-0.25, 0.25), w(0, 1);
    std::vector<Rayd> rays;
    for (int i = 0; i < 60000; ++i) {
      glm::vec3 o(c + glm::dvec3(u(rng), u(rng), u(rng)));
      uint32_t row = uint32_t(rng() % t.size());
      glm::vec3 target{};
      if (i % 3 == 0) {
        target = t.p0(row);  // a vertex
      } else if (i % 3 == 1) {
        float a = float(w(rng));  // a float point on an edge
        target =
            glm::vec3(glm::dvec3(t.p0(row)) * double(1 - a) + glm::dvec3(t.p1(row)) * double(a));
      } else {
        target = glm::vec3(glm::dvec3(o) + glm::dvec3(u(rng), u(rng), u(rng)));
      }
      glm::dvec3 d = glm::dvec3(target) - glm::dvec3(o);
      if (length_squared(d) == 0) continue;
      rays.push_back({glm::dvec3(o), normalize(d)});
    }
    RayStream stream = RayStream::from(rays);
    HitStream hits;
    tracer().closest(s, bvh, stream, hits);
    int escapes = 0;
    for (std::size_t i = 0; i < rays.size(); ++i)
      escapes += hits.prim[i] == PrimRef::kInvalidBits;
    EXPECT_EQ(escapes, 0) << "offset " << offset << " of " << rays.size() << " rays";
  }
}

TEST_P(SimdTracerTest, OcclusionMatchesReference) {
  Scene s = random_scene(18, 300, 10);
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  std::vector<Rayd> rays = random_rays(19, 5000, 12);
  for (auto& r : rays)
    r.tmax = 4.0;
  RayStream stream = RayStream::from(rays);
  HitStream hits;
  tracer().occluded(s, bvh, stream, hits);
  int disagreements_outside_band = 0, band = 0, occluded = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    Rayd ray = round_to_float(rays[i]);
    bool ref = any_hit_ref(s, ray);
    occluded += ref;
    // Occlusion is settled wherever the closest hit is: a clear hit or a clear miss.
    bool in_band =
        testing::classify_closest(s, ray, /*skip_far_bounds=*/true).cls == testing::RayClass::kBand;
    band += in_band;
    disagreements_outside_band += !in_band && ref != (hits.prim[i] == 0);
  }
  EXPECT_GT(occluded, 100);
  EXPECT_EQ(disagreements_outside_band, 0) << band << " rays in the band";
}

// Occlusion aimed at a primitive (RayStream::aim): the aim does not block, what lies before it
// does. Each ray is aimed at its first surface A (tmax just past it: clear), at its second B
// (tmax just past B: blocked by A, clear if B is A's far side) or at nothing (plain occlusion),
// against the reference on the float ray: blocked when the closest hit is not the aim. Rays
// with another surface within 1e-4 past the aimed hit are left out (found first, it may block:
// SimdTracer::occluded), as are rays in the kernels' error band.
TEST_P(SimdTracerTest, AimedOcclusionMatchesReference) {
  Scene s = random_scene(18, 300, 10);
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  std::vector<Rayd> rays;
  std::vector<uint32_t> aims;
  std::vector<uint8_t> want;
  int kinds[3] = {};
  for (Rayd r : random_rays(19, 12000, 12)) {
    r = round_to_float(r);
    if (testing::classify_closest(s, r, true).cls == testing::RayClass::kBand) continue;
    Hit a = closest_hit_ref(s, r);
    Rayd past_a = r;
    past_a.tmin = a.t;
    Hit b = a.hit() ? closest_hit_ref(s, past_a) : Hit{};
    Rayd past_b = r;
    past_b.tmin = b.t;
    Hit c = b.hit() ? closest_hit_ref(s, past_b) : Hit{};
    const int kind = int(rays.size() % 3);
    if (kind == 0 && a.hit() && !(b.t <= a.t * (1 + 1e-4))) {
      r.tmax = float(a.t * (1 + 1e-5));
      rays.push_back(r), aims.push_back(a.prim.bits()), want.push_back(0);
    } else if (kind == 1 && b.hit() && !(c.t <= b.t * (1 + 1e-4))) {
      r.tmax = float(b.t * (1 + 1e-5));
      rays.push_back(r), aims.push_back(b.prim.bits()), want.push_back(b.prim != a.prim);
    } else if (kind == 2) {
      r.tmax = 4.0;
      rays.push_back(r), aims.push_back(PrimRef::kInvalidBits), want.push_back(any_hit_ref(s, r));
    } else {
      continue;
    }
    ++kinds[kind];
  }
  RayStream stream = RayStream::from(rays);
  stream.aim.assign(aims.begin(), aims.end());
  HitStream hits;
  tracer().occluded(s, bvh, stream, hits);
  for (std::size_t i = 0; i < rays.size(); ++i)
    ASSERT_EQ(hits.prim[i] == 0, want[i] == 1) << "ray " << i << " aim " << aims[i];
  for (int k : kinds)
    EXPECT_GT(k, 800);
  EXPECT_GT(std::count(want.begin(), want.end(), 1), 60);
}

// The ray's permutation for the watertight test (RayShear): the axis of largest |d| and
// whether d is negative along it. Packets whose rays share it take other code paths (permuted
// loads of columns, one near plane per axis) than packets that mix them.
int axes_key(const Rayd& r) {
  glm::vec3 d(r.d);
  float a[3] = {std::abs(d.x), std::abs(d.y), std::abs(d.z)};
  int kz = (a[0] >= a[1] && a[0] >= a[2]) ? 0 : (a[1] >= a[2] ? 1 : 2);
  int octant = (d.x < 0) | (d.y < 0) << 1 | (d.z < 0) << 2;
  return kz * 8 + octant;
}

// Coherent packets (every active lane with the same axes and octant) and mixed ones run
// different code with the same roundings: the same rays traced in both groupings give the
// same answers, bit for bit, for closest hit and for occlusion. Invalid rays of other
// octants sit inside the coherent packets (they must not break the coherence of the active
// lanes), some rays start at tmin > 0, and the last packet is partly filled.
TEST_P(SimdTracerTest, CoherentAndMixedPacketsAnswerBitForBitAlike) {
  if (!packets()) GTEST_SKIP() << "a single ray has one permutation and octant by construction";
  Scene s = random_scene(23, 300, 10);
  testing::add_closed_uv_sphere(s, 24, 16, 32, {2, -1, 3});
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  std::vector<Rayd> valid = random_rays(25, 20003, 12);
  for (std::size_t i = 0; i < valid.size(); i += 3)
    valid[i].tmax = 6.0;  // short segments too: occlusion needs some misses
  for (std::size_t i = 1; i < valid.size(); i += 5)
    valid[i].tmin = 0.5;
  std::stable_sort(valid.begin(), valid.end(),
                   [](const Rayd& a, const Rayd& b) { return axes_key(a) < axes_key(b); });
  // Grouped: the sorted valid rays with an invalid ray (tmin > tmax) of a random direction at
  // every 7th place. Mixed: the same rays in a random order.
  std::vector<Rayd> invalid = random_rays(26, int(valid.size() / 6), 12);
  std::vector<Rayd> grouped;
  for (std::size_t i = 0, j = 0; i < valid.size();) {
    if (grouped.size() % 7 == 3 && j < invalid.size()) {
      grouped.push_back(invalid[j++]);
      grouped.back().tmin = 2, grouped.back().tmax = 1;
    } else {
      grouped.push_back(valid[i++]);
    }
  }
  std::vector<std::size_t> where(grouped.size());  // mixed[k] = grouped[where[k]]
  std::iota(where.begin(), where.end(), 0);
  std::shuffle(where.begin(), where.end(), std::mt19937_64(27));
  std::vector<Rayd> mixed;
  for (std::size_t k : where)
    mixed.push_back(grouped[k]);
  // How many packets have one key over their valid rays: few mixed, nearly all grouped.
  const std::size_t w = std::size_t(tracer().width());
  auto coherent_packets = [w](const std::vector<Rayd>& rays) {
    std::size_t n = 0;
    for (std::size_t i = 0; i + w <= rays.size(); i += w) {
      std::set<int> keys;
      for (std::size_t k = 0; k < w; ++k)
        if (rays[i + k].tmin <= rays[i + k].tmax) keys.insert(axes_key(rays[i + k]));
      n += keys.size() == 1;
    }
    return n;
  };
  const std::size_t packets = grouped.size() / w;
  EXPECT_LT(coherent_packets(mixed), packets / 4 + 1);
  EXPECT_GT(coherent_packets(grouped), packets * 8 / 10);
  for (bool any_hit : {false, true}) {
    HitStream a, b;
    RayStream sa = RayStream::from(grouped), sb = RayStream::from(mixed);
    any_hit ? tracer().occluded(s, bvh, sa, a) : tracer().closest(s, bvh, sa, a);
    any_hit ? tracer().occluded(s, bvh, sb, b) : tracer().closest(s, bvh, sb, b);
    int differ = 0, hits = 0;
    for (std::size_t k = 0; k < mixed.size(); ++k) {
      std::size_t i = where[k];
      hits += a.prim[i] != PrimRef::kInvalidBits;
      // Occlusion answers only whether something is hit: which hit is found first, and its
      // t, depend on the order the packet visits nodes, which its lanes' directions choose.
      bool same_t = any_hit || std::memcmp(&a.t[i], &b.t[k], sizeof(float)) == 0;
      differ += a.prim[i] != b.prim[k] || !same_t;
    }
    EXPECT_EQ(differ, 0) << (any_hit ? "occlusion" : "closest hit");
    EXPECT_GT(hits, 2000);
    EXPECT_LT(hits, int(mixed.size()) - 2000);
  }
}

// The counting traversal gives the same answers as the production one, and its counts add
// up: on a one-sphere scene the root is the only node, a leaf with one primitive.
TEST_P(SimdTracerTest, CountedTraversalAnswersAlikeAndCountsExactly) {
  Scene s = random_scene(7, 40);
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  RayStream stream = RayStream::from(random_rays(8, 1000, 12));
  const SimdTracer tracer = this->tracer();
  HitStream plain, counted;
  for (bool any_hit : {false, true}) {
    any_hit ? tracer.occluded(s, bvh, stream, plain) : tracer.closest(s, bvh, stream, plain);
    TraversalCounters c = tracer.trace_counted(s, bvh, stream, counted, any_hit);
    EXPECT_EQ(plain.prim, counted.prim);
    EXPECT_EQ(plain.t, counted.t);
    EXPECT_EQ(c.rays, 1000u);
    EXPECT_EQ(c.width, packets() ? tracer.width() : kWideArity);
    EXPECT_GE(c.node_tests, c.packets);
    EXPECT_LE(c.lanes_overlap, c.lanes_active);
    EXPECT_LE(c.lanes_active, c.node_tests * uint64_t(c.width));
  }
  Scene one = parse_scene("camera 0 0 5 1\nsphere 0 0 0 1\n", "one.scn").scene;
  Bvh one_bvh = build_bvh_and_reorder(one, kWithWideNodes);
  std::vector<Rayd> down(37, Rayd{{0, 0, 5}, {0, 0, -1}});
  TraversalCounters c =
      tracer.trace_counted(one, one_bvh, RayStream::from(down), counted, /*any_hit=*/false);
  // Packets: ceil(37 / W) packets, each testing the root leaf once. Single rays: 37 rays, each
  // testing the one wide node (whose one child is that leaf) and the leaf.
  uint64_t traced = packets() ? (37 + c.width - 1) / c.width : 37;
  EXPECT_EQ(c.packets, traced);
  EXPECT_EQ(c.node_tests, traced);
  EXPECT_EQ(c.leaf_visits, traced);
  EXPECT_EQ(c.prim_tests, traced);
  EXPECT_EQ(c.lanes_overlap, 37u);
  EXPECT_FLOAT_EQ(counted.t[36], 4.0f);
}

INSTANTIATE_TEST_SUITE_P(EveryIsa, SimdTracerTest,
                         ::testing::Values(TracerConfig{Isa::kSse42, Traversal::kPackets},
                                           TracerConfig{Isa::kAvx2, Traversal::kPackets},
                                           TracerConfig{Isa::kAvx512, Traversal::kPackets},
                                           TracerConfig{Isa::kSse42, Traversal::kSingleRays},
                                           TracerConfig{Isa::kAvx2, Traversal::kSingleRays},
                                           TracerConfig{Isa::kAvx512, Traversal::kSingleRays}),
                         [](const auto& info) {
                           std::string n(isa_name(info.param.isa));
                           n.erase(std::remove(n.begin(), n.end(), '.'), n.end());
                           return n + "_" + std::string(traversal_name(info.param.traversal));
                         });

}  // namespace
}  // namespace raylane
