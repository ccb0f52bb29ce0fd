// The CSG lane kernel (csg_packet.h) at every instruction set and traversal against the double
// reference (csg.cpp), on the spec's examples and hard cases. A ray is judged leaf by leaf: where
// every leaf's line test is outside its kind's error band (support/error_bands) and the leaves'
// ends lie apart, the kernel must name the reference's leaf, with t inside the band the error
// analysis gives that leaf's kernel; elsewhere either answer is allowed, and counted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>

#include "raylane/bvh/bvh.h"
#include "raylane/core/ray_offset.h"
#include "raylane/render/camera/camera.h"
#include "raylane/scene/parser.h"
#include "raylane/trace/brute_force.h"
#include "raylane/trace/simd_tracer.h"
#include "raylane/trace/tracer.h"
#include "support/error_bands.h"
#include "support/paths.h"
#include "support/random_scene.h"

namespace raylane {
namespace {

using testing::RayClass;
using testing::round_to_float;

constexpr double kInf = std::numeric_limits<double>::infinity();
const BvhConfig kWithWideNodes{.wide_nodes = true};

// The spec's examples and the hard cases, side by side along x.
const char* kBlocks =
    "camera 0 0 20 0.5\n"
    "brdf 0.5 0.5 0.5 0 0 0 10\n"
    "csg\nsphere 0 0 -0.5 1\nsphere 0 0 0.5 1\nintersect\nend\n"            // lens
    "csg\nbox 2 -1 -1 2 2 2\ncylinder 3 0 -2 0 0 4 0.5\ndifference\nend\n"  // drilled
    "csg\nsphere 6 0 0 1\nsphere 6.8 0.5 0.5 0.6\ndifference\nend\n"        // bitten
    "csg\nbox 8 -1 -1 1 2 2\nbox 9 -1 -1 1 2 2\nunion\nend\n"               // touching
    "csg\nsphere 12 0 0 1\nsphere 12 0 0 1\ndifference\nend\n"              // A − A
    "csg\nbox -3 -1 -1 2 2 2\nsphere -2 0 0 2\ndifference\nend\n"           // B ⊃ A
    "csg\nsphere 0 4 0 1.2\nsphere 0 4 0 0.8\ndifference\nbox -2 4 -2 4 2 4\ndifference\nend\n"
    // (B ∩ C) ∪ A, B ∩ C empty: B's top coincides with A's, and only A's bounds the solid.
    "csg\nbox 3 3 -1 1 1 1\nbox 8 8 8 1 1 1\nintersect\nbox 3 3 -1 2 2 1\nunion\nend\n";

// Blocks overlapping blocks, in both orders: a block's farther boundary must not replace a
// nearer hit already found.
const char* kOverlapping =
    "csg\nsphere 8 4 0 1\nend\ncsg\nbox 7.5 3.5 -0.5 1.2 1 1\nend\n"
    "csg\nbox 11.5 3.5 -0.5 1.2 1 1\nend\ncsg\nsphere 12 4 0 1\nend\n";

// 30 leaves: spheres and boxes along a ring, mostly joined, some cut.
std::string thirty_leaves() {
  std::ostringstream s;
  s << "csg\n";
  for (int i = 0; i < 30; ++i) {
    double a = i * 2 * M_PI / 30, x = 5 + 2 * std::cos(a), y = -5 + 2 * std::sin(a);
    if (i % 3 == 1)
      s << "box " << x - 0.3 << ' ' << y - 0.3 << " -0.3 0.6 0.6 0.6\n";
    else
      s << "sphere " << x << ' ' << y << " 0 0.45\n";
    if (i > 0) s << (i % 7 == 3 ? "difference\n" : i % 11 == 5 ? "intersect\n" : "union\n");
  }
  s << "end\n";
  return s.str();
}

Scene csg_scene(bool overlapping = true) {
  auto p = parse_scene(std::string(kBlocks) + (overlapping ? kOverlapping : "") + thirty_leaves(),
                       "csg.scn");
  EXPECT_TRUE(p.ok());
  return std::move(p.scene);
}

testing::PrimVerdict leaf_verdict(const CsgTable& c, uint32_t leaf, const Rayd& ray) {
  uint32_t r = c.leaf_row[leaf];
  return c.leaf_kind[leaf] == kCsgSphere ? testing::classify(c.spheres, r, ray)
         : c.leaf_kind[leaf] == kCsgBox  ? testing::classify(c.boxes, r, ray)
                                         : testing::classify(c.cylinders, r, ray);
}

// Whether the ray is decided for the kernel (see the file's comment), and for a hit the
// interval its t must lie in.
bool clear_ray(const Scene& s, const Rayd& ray, const Hit& ref, testing::Interval& t_band) {
  const CsgTable& c = s.table<Csg>();
  std::vector<double> ends{ray.tmin};
  Rayd line = ray;
  line.tmin = -1e30, line.tmax = 1e30;
  for (uint32_t leaf = 0; leaf < c.leaves(); ++leaf) {
    if (leaf_verdict(c, leaf, line).cls == RayClass::kBand) return false;  // tangent-ish
    double t0, t1;
    csg_leaf_interval_ref(c, leaf, ray, t0, t1);
    for (double e : {t0, t1})
      if (std::isfinite(e)) ends.push_back(e);
  }
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  for (std::size_t i = 1; i < ends.size(); ++i)  // ends apart by far more than float error
    if (ends[i] - ends[i - 1] <= 0x1p-12 * std::max(std::abs(ends[i]), 1.0)) return false;
  if (!ref.hit()) return true;
  // The hit leaf's own verdict in a window around the hit holding no other end.
  Rayd window = ray;
  double half = 0x1p-13 * std::max(std::abs(ref.t), 1.0);
  window.tmin = ref.t - half, window.tmax = ref.t + half;
  testing::PrimVerdict v = leaf_verdict(c, ref.prim.row(), window);
  if (v.cls != RayClass::kClearHit) return false;
  t_band = v.t;
  return true;
}

// Rays from around the scene aimed into it, with invalid rays among them (inactive lanes).
std::vector<Rayd> rays_at(const Scene& s, int n, uint32_t seed) {
  Bounds3f b = s.bounds();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Rayd> out;
  for (int i = 0; i < n; ++i) {
    glm::dvec3 target(b.lo.x + u(rng) * (b.hi.x - b.lo.x), b.lo.y + u(rng) * (b.hi.y - b.lo.y),
                      b.lo.z + u(rng) * (b.hi.z - b.lo.z));
    glm::dvec3 o = i % 5 == 0
                       ? target  // starting inside or near a solid
                       : glm::dvec3(5, 0, 0) +
                             25.0 * normalize(glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
    glm::dvec3 d = i % 5 == 0 ? glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) : target - o;
    Rayd r{o, d, 0, kInf};
    if (i % 97 == 3) r.o.x = std::nan("");
    if (i % 89 == 4) r.d = {0, 0, 0};
    out.push_back(round_to_float(r));
  }
  return out;
}

struct CsgConfig {
  Isa isa;
  Traversal traversal;
};

class CsgPacketTest : public ::testing::TestWithParam<CsgConfig> {
 protected:
  void SetUp() override {
    if (!isa_supported(GetParam().isa))
      GTEST_SKIP() << "this CPU lacks " << isa_name(GetParam().isa);
  }
  SimdTracer tracer() const { return SimdTracer(GetParam().isa, GetParam().traversal); }
};

TEST_P(CsgPacketTest, ClosestHitsAgreeWithTheReference) {
  Scene s = csg_scene();
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  std::vector<Rayd> rays = rays_at(s, 20001, 3);  // the last packet partly filled
  HitStream hits;
  tracer().closest(s, bvh, RayStream::from(rays), hits);
  int clear = 0, band = 0, band_disagreements = 0, hits_seen = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    ASSERT_FALSE(std::isnan(hits.t[i])) << i;
    Hit ref = closest_hit_ref(s, rays[i]);
    bool hit = hits.prim[i] != PrimRef::kInvalidBits;
    if (!ray_is_valid(rays[i])) {
      EXPECT_FALSE(hit) << i;
      continue;
    }
    testing::Interval t_band;
    if (!clear_ray(s, rays[i], ref, t_band)) {
      ++band;
      band_disagreements += hit != ref.hit() || (hit && hits.prim[i] != ref.prim.bits());
      continue;
    }
    ++clear;
    hits_seen += hit;
    ASSERT_EQ(hit, ref.hit()) << i << " ref t " << ref.t << " " << to_string(ref.prim) << " o "
                              << rays[i].o.x << " " << rays[i].o.y << " " << rays[i].o.z << " d "
                              << rays[i].d.x << " " << rays[i].d.y << " " << rays[i].d.z;
    if (!hit) continue;
    EXPECT_EQ(to_string(PrimRef::from_bits(hits.prim[i])), to_string(ref.prim)) << i;
    EXPECT_GE(hits.t[i], t_band.lo) << i;
    EXPECT_LE(hits.t[i], t_band.hi) << i;
  }
  EXPECT_GT(hits_seen, clear / 10);
  EXPECT_GT(clear, int(rays.size()) * 8 / 10);
  std::printf("[ bands    ] %d clear rays (%d hits), %d in the band, %d of them disagreeing\n",
              clear, hits_seen, band, band_disagreements);
}

TEST_P(CsgPacketTest, OcclusionAgreesWithTheReference) {
  Scene s = csg_scene();
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  std::vector<Rayd> rays = rays_at(s, 5001, 4);
  for (std::size_t i = 0; i < rays.size(); ++i)
    rays[i].tmax = i % 2 ? 30.0 : 25.0;
  HitStream hits;
  tracer().occluded(s, bvh, RayStream::from(rays), hits);
  int checked = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    Hit ref = closest_hit_ref(s, rays[i]);
    testing::Interval t_band;
    if (!ray_is_valid(rays[i]) || !clear_ray(s, rays[i], ref, t_band)) continue;
    if (ref.hit() && std::abs(ref.t - rays[i].tmax) < 1e-3 * ref.t) continue;  // at the end
    ++checked;
    EXPECT_EQ(hits.prim[i] != PrimRef::kInvalidBits, any_hit_ref(s, rays[i])) << i;
  }
  EXPECT_GT(checked, 4000);
}

// The depth image of scenes/csg.scn (the spec's examples): where the kernel and the reference
// see the same leaf, t agrees to 1e-4 relative; the pixels where they see different surfaces
// (silhouettes, coincident edges) are few.
TEST_P(CsgPacketTest, DepthImageOfTheExamplesAgreesWithTheReference) {
  auto p = load_scene_file(testing::source_path("scenes/csg.scn"));
  ASSERT_TRUE(p.ok());
  Bvh bvh = build_bvh_and_reorder(p.scene, kWithWideNodes);
  Camera cam = Camera::from_scene(p.scene);
  std::vector<Rayd> rays;
  for (uint32_t y = 0; y < cam.height; ++y)
    for (uint32_t x = 0; x < cam.width; ++x)
      rays.push_back(round_to_float(cam.ray_through(x + 0.5, y + 0.5)));
  HitStream hits;
  tracer().closest(p.scene, bvh, RayStream::from(rays), hits);
  int csg_pixels = 0, other_surface = 0, t_off = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    Hit ref = closest_hit_ref(p.scene, rays[i]);
    if (ref.hit() && ref.prim.tag() == tag_of<Csg>) ++csg_pixels;
    if (hits.prim[i] != ref.prim.bits()) {
      ++other_surface;
      continue;
    }
    if (ref.hit()) t_off += std::abs(hits.t[i] - ref.t) > 1e-4 * ref.t;
  }
  std::printf("[ depth    ] %zu pixels, %d on csg blocks, %d seeing another surface\n", rays.size(),
              csg_pixels, other_surface);
  EXPECT_GT(csg_pixels, int(rays.size()) / 10);
  EXPECT_EQ(t_off, 0);
  EXPECT_LT(other_surface, int(rays.size()) / 1000);
}

// Secondary rays from the blocks' surfaces with the render's offsets (core/ray_offset.h):
// one continuing into the solid must meet its boundary from inside (a front face or a miss
// would be a leak through the surface it entered), one reflected off it must not meet a
// surface from inside (acne on the surface it left).
TEST_P(CsgPacketTest, SecondaryRaysNeitherLeakNorReHitWithTheRenderOffsets) {
  Scene s = csg_scene(/*overlapping=*/false);  // solids apart: inside one is inside no other
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  Tracer tracer(s, bvh, TracerBackend::kPacket, GetParam().isa);
  std::vector<Rayd> first = rays_at(s, 20000, 5), into, out;
  std::vector<Hit> hits;
  tracer.closest(first, hits);
  for (std::size_t i = 0; i < first.size(); ++i) {
    const Hit& h = hits[i];
    if (!h.hit() || h.prim.tag() != tag_of<Csg> || !h.front_face) continue;
    glm::dvec3 err = hit_point_error(first[i], h.t), n = h.surface.ng, d = normalize(first[i].d);
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
  EXPECT_GT(into.size(), 2000u);
  EXPECT_EQ(leaks, 0);
  EXPECT_EQ(acne, 0);
}

INSTANTIATE_TEST_SUITE_P(EveryIsa, CsgPacketTest,
                         ::testing::Values(CsgConfig{Isa::kSse42, Traversal::kPackets},
                                           CsgConfig{Isa::kAvx2, Traversal::kPackets},
                                           CsgConfig{Isa::kAvx512, Traversal::kPackets},
                                           CsgConfig{Isa::kSse42, Traversal::kSingleRays},
                                           CsgConfig{Isa::kAvx2, Traversal::kSingleRays},
                                           CsgConfig{Isa::kAvx512, Traversal::kSingleRays}),
                         [](const auto& info) {
                           std::string n(isa_name(info.param.isa));
                           n.erase(std::remove(n.begin(), n.end(), '.'), n.end());
                           return n + "_" + std::string(traversal_name(info.param.traversal));
                         });

}  // namespace
}  // namespace raylane
