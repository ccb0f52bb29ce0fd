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
#include "raylane/prims/sdf_packet.h"
#include "raylane/render/camera/camera.h"
#include "raylane/scene/parser.h"
#include "raylane/trace/brute_force.h"
#include "raylane/trace/simd_tracer.h"
#include "raylane/trace/tracer.h"
#include "support/paths.h"
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

double origin_norm(const Rayd& r) {
  return std::max({std::abs(r.o.x), std::abs(r.o.y), std::abs(r.o.z)});
}

// How far two marches of the same ray may stop apart: each stops where |distance| first falls
// below the tolerance (sdf.h), so anywhere in [t* − tol/(|d|·cos), t*] before the surface at t*
// met at that cosine, plus the float distance's rounding (below the tolerance's floor of 8
// ulps of the point: 1 ulp more is allowed, and 1 % for float t).
double march_band(const Rayd& r, double t, double cosine) {
  double len = length(r.d), tol = sdf_tolerance(t * len, origin_norm(r)) / len;
  return tol * 1.01 / std::max(cosine, 1e-6) + 0x1p-23 * (origin_norm(r) / len + t);
}

// The float lanes against the double reference through the brute-force oracle: where both hit
// an sdf block, t within the band of two marches and the leaf the reference names; a hit
// against a miss only at a silhouette (the reference's hit met at a cosine below 0.05, or the
// lanes' point within the tolerance of the surface in double); a hit on another kind only where
// the sdf surface is within the band of it. Returns the sdf hits and the silhouettes; counts
// the hits naming another leaf than the reference's in *seams.
std::pair<int, int> expect_lanes_are_the_reference(const Scene& s, const std::vector<Rayd>& rays,
                                                   const HitStream& hits,
                                                   int* seam_count = nullptr) {
  const SdfTable& table = s.table<Sdf>();
  int sdf_hits = 0, silhouettes = 0, seams = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    EXPECT_FALSE(std::isnan(hits.t[i])) << i;
    const Rayd& r = rays[i];
    Hit ref = closest_hit_ref(s, r);
    bool hit = hits.prim[i] != PrimRef::kInvalidBits;
    PrimRef got = PrimRef::from_bits(hits.prim[i]);
    if (!ray_is_valid(r)) {
      EXPECT_FALSE(hit) << i;
      continue;
    }
    double cosine = ref.hit() ? std::abs(dot(ref.surface.ng, normalize(r.d))) : 0;
    if (hit != ref.hit()) {
      ++silhouettes;
      if (ref.hit()) {
        EXPECT_LT(cosine, 0.05) << i;
      } else if (got.tag() != tag_of<Sdf>) {
        ADD_FAILURE() << i << ": " << to_string(got) << " hit, the reference misses";
      } else {
        double d = sdf_distance_ref(table, table.leaf_block[got.row()], r.at(hits.t[i]));
        EXPECT_LT(std::abs(d), sdf_tolerance(hits.t[i] * length(r.d), origin_norm(r)) * 1.01) << i;
      }
      continue;
    }
    if (!hit) continue;
    if (got.tag() != tag_of<Sdf> && ref.prim.tag() != tag_of<Sdf>) {
      EXPECT_EQ(to_string(got), to_string(ref.prim)) << i;
      continue;
    }
    sdf_hits += got.tag() == tag_of<Sdf>;
    EXPECT_NEAR(hits.t[i], ref.t, march_band(r, ref.t, cosine)) << i;
    if (got.tag() == tag_of<Sdf> && ref.prim.tag() == tag_of<Sdf> && got.row() != ref.prim.row()) {
      // Where two leaves are nearly as near, the two stopping points may see different ones:
      // leaf distances move by at most the distance between the points (|∇| = 1), so the
      // leaf named is at most twice that, and the tolerance for rounding, farther than the
      // reference's at its point.
      glm::dvec3 p = r.at(ref.t);
      double apart = std::abs(hits.t[i] - ref.t) * length(r.d);
      double slack = 2 * apart + sdf_tolerance(ref.t * length(r.d), origin_norm(r));
      EXPECT_EQ(table.leaf_block[got.row()], table.leaf_block[ref.prim.row()]) << i;
      EXPECT_LE(std::abs(sdf_leaf_distance_ref(table, got.row(), p)),
                std::abs(sdf_leaf_distance_ref(table, ref.prim.row(), p)) + slack)
          << i;
      ++seams;
    }
  }
  if (seam_count) *seam_count = seams;
  return {sdf_hits, silhouettes};
}

TEST_P(SdfPacketTest, ClosestHitsAreTheReferences) {
  Scene s = sdf_scene();
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  std::vector<Rayd> rays = rays_at(s, 3001, 3);  // the last packet partly filled
  HitStream hits;
  tracer().closest(s, bvh, RayStream::from(rays), hits);
  auto [sdf_hits, silhouettes] = expect_lanes_are_the_reference(s, rays, hits);
  std::printf("[ lanes    ] %d sdf hits, %d hit/miss at silhouettes\n", sdf_hits, silhouettes);
  EXPECT_GT(sdf_hits, int(rays.size()) / 5);
  EXPECT_LT(silhouettes, int(rays.size()) / 100);
}

// kBlocks' shapes scaled by `scale` about the origin and moved by `offset` along (1, 1, 1).
Scene moved_scene(double scale, double offset) {
  char text[1024];
  auto x = [&](double v) { return offset + scale * v; };
  auto v = [&](double v) { return scale * v; };
  std::snprintf(text, sizeof text,
                "camera 0 0 20 0.5\nbrdf 0.5 0.5 0.5 0 0 0 10\n"
                "sdf\ntorus %.17g %.17g %.17g 0.3 1 0.2 %.17g %.17g\nend\n"
                "sdf\nsphere %.17g %.17g %.17g %.17g\nsphere %.17g %.17g %.17g %.17g\n"
                "smoothunion %.17g\nend\n"
                "sdf\nbox %.17g %.17g %.17g %.17g %.17g %.17g\nsphere %.17g %.17g %.17g "
                "%.17g\nintersect\ncylinder %.17g %.17g %.17g 0 0 %.17g %.17g\n"
                "smoothdifference %.17g\nend\n",
                x(0), x(0), x(0), v(1.2), v(0.35), x(3), x(0), x(0), v(0.8), x(4), x(0.3), x(0),
                v(0.6), v(0.5), x(6), x(-1), x(-1), v(2), v(2), v(2), x(7), x(0), x(0), v(1.25),
                x(7), x(0), x(-2), v(4), v(0.5), v(0.2));
  auto p = parse_scene(text, "moved.scn");
  EXPECT_TRUE(p.ok());
  return std::move(p.scene);
}

// Rays from a sphere around the scene's bounds at targets inside them; one in four from inside
// the bounds in a random direction.
std::vector<Rayd> rays_around(const Scene& s, int n, uint32_t seed) {
  Bounds3f b = s.bounds();
  glm::dvec3 lo(b.lo), hi(b.hi), c = 0.5 * (lo + hi);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Rayd> out;
  for (int i = 0; i < n; ++i) {
    glm::dvec3 target = lo + glm::dvec3(u(rng), u(rng), u(rng)) * (hi - lo);
    glm::dvec3 around = normalize(glm::dvec3(u(rng), u(rng), u(rng)) - 0.5);
    glm::dvec3 o = i % 4 == 0 ? target : c + 1.5 * length(hi - lo) * around;
    glm::dvec3 d = i % 4 == 0 ? around : target - o;
    out.push_back(round_to_float(Rayd{o, d, 0, kInf}));
  }
  return out;
}

// The tolerance scales: the shapes 1e4 from the origin and at 1e-3 of their size (both), hit as
// the reference hits them, and never NaN.
TEST_P(SdfPacketTest, FarAndTinyShapesAreTheReferences) {
  for (double scale : {1.0, 1e-3}) {
    for (double offset : {0.0, 1e4}) {
      SCOPED_TRACE(::testing::Message() << "scale " << scale << ", at " << offset);
      Scene s = moved_scene(scale, offset);
      Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
      std::vector<Rayd> rays = rays_around(s, 1000, 9);
      HitStream hits;
      tracer().closest(s, bvh, RayStream::from(rays), hits);
      auto [sdf_hits, silhouettes] = expect_lanes_are_the_reference(s, rays, hits);
      EXPECT_GT(sdf_hits, 200);
      EXPECT_LT(silhouettes, 20);
    }
  }
}

// Rays parallel to a torus's axis at radius ρ near its inner rim R − r and its outer silhouette
// R + r, and rays from inside the solids: the reference's answers, and no ray runs out of steps.
TEST_P(SdfPacketTest, GrazingRimsAndRaysFromInsideAreTheReferences) {
  Scene s = sdf_scene();
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  std::vector<Rayd> rays;
  const glm::dvec3 axis = normalize(glm::dvec3(0.3, 1, 0.2));
  const glm::dvec3 e1 = normalize(cross(axis, glm::dvec3(1, 0, 0))), e2 = cross(axis, e1);
  for (double rim : {1.2 - 0.35, 1.2 + 0.35})
    for (double delta : {-1e-2, -1e-3, -1e-4, -1e-6, 0.0, 1e-6, 1e-4, 1e-3, 1e-2})
      for (int k = 0; k < 16; ++k) {
        double a = k * 2 * M_PI / 16, rho = rim + delta;
        glm::dvec3 o = rho * (std::cos(a) * e1 + std::sin(a) * e2) + 3.0 * axis;
        rays.push_back(round_to_float(Rayd{o, -axis, 0, kInf}));
      }
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 400; ++i) {  // inside the smooth union and the carved box
    glm::dvec3 o = i % 2 ? glm::dvec3(3.3, 0.1, 0) : glm::dvec3(6.4, 0.6, 0.6);
    o += 0.2 * glm::dvec3(u(rng), u(rng), u(rng));
    rays.push_back(round_to_float(Rayd{o, {u(rng), u(rng), u(rng)}, 0, kInf}));
  }
  HitStream hits;
  SdfMarchCounts before = sdf_march_counts();
  tracer().closest(s, bvh, RayStream::from(rays), hits);
  SdfMarchCounts after = sdf_march_counts();
  expect_lanes_are_the_reference(s, rays, hits);
  EXPECT_GT(after.marches, before.marches);
  EXPECT_EQ(after.out_of_steps, before.out_of_steps);
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
// continuing into the solid must meet its boundary from inside, one reflected off it must not
// meet a surface from inside (acne). Without moving the hit point onto the surface (sdf.cpp,
// surface_ref), 127 of 1171 leaked: the march stops up to its tolerance outside. A ray into the
// solid leaks where it misses, or meets a front face at a point outside the block it left (it
// passed through that block's surface). A front face inside the block is another solid's (the
// analytic sphere overlapping the torus): 10 of the 11 "leaks" the old count (any front face)
// found were those, not seams. A miss by steps — the reference marcher, from the same origin,
// also running out of its 256 steps (a ray crawling along the inside of the carved box's
// blend, at a grazing exit: Hart 1996, §4) — is counted apart, and must be the reference's.
TEST_P(SdfPacketTest, SecondaryRaysNeitherLeakNorReHitWithTheRenderOffsets) {
  Scene s = sdf_scene();
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  Tracer tracer(s, bvh, TracerBackend::kPacket, GetParam().isa);
  std::vector<Rayd> first = rays_at(s, 3000, 5), into, out;
  std::vector<std::size_t> from;  // the first ray of each ray into a solid
  std::vector<Hit> hits;
  tracer.closest(first, hits);
  for (std::size_t i = 0; i < first.size(); ++i) {
    const Hit& h = hits[i];
    if (!h.hit() || h.prim.tag() != tag_of<Sdf> || !h.front_face) continue;
    glm::dvec3 err = hit_point_error(first[i], h.t), n = h.surface.ng, d = normalize(first[i].d);
    if (std::abs(dot(d, n)) < 0.1) continue;  // silhouettes aside: the march stops short there
    into.push_back({offset_ray_origin(h.surface.p, err, n, -n), d});
    from.push_back(i);
    out.push_back({offset_ray_origin(h.surface.p, err, n, n), d - 2 * dot(d, n) * n});
  }
  std::vector<Hit> in_hits, out_hits;
  tracer.closest(into, in_hits);
  tracer.closest(out, out_hits);
  const SdfTable& st = s.table<Sdf>();
  int leaks = 0, acne = 0, inner = 0, by_steps = 0;
  for (std::size_t i = 0; i < in_hits.size(); ++i) {
    const Hit& h = in_hits[i];
    const uint32_t blk = st.leaf_block[hits[from[i]].prim.row()];
    if (!h.hit()) {
      bool ref_ran_out = false;
      for (uint32_t row = 0; row < st.size(); ++row)
        if (st.block[row] == blk) {
          Sdf::LeafHit ref = Sdf::hit_ref(st, row, into[i]);
          ref_ran_out = !(ref.t < kInf) && ref.steps == uint32_t(kSdfMaxSteps);
        }
      (ref_ran_out ? by_steps : leaks) += 1;
    } else if (h.front_face) {
      bool in_block = h.prim.tag() != tag_of<Sdf> && sdf_distance_ref(st, blk, h.surface.p) < 0;
      (in_block ? inner : leaks) += 1;
    }
  }
  for (const Hit& h : out_hits)
    acne += h.hit() && !h.front_face;
  std::printf(
      "[ offsets  ] %zu rays into the solids, %d leaking, %d meeting another solid inside, %d "
      "missing by steps as the reference does; %zu reflected, %d re-hitting\n",
      into.size(), leaks, inner, by_steps, out.size(), acne);
  EXPECT_GT(into.size(), 300u);
  EXPECT_EQ(leaks, 0);
  EXPECT_GT(inner, 0);     // the overlapping sphere is met: the count above is not vacuous
  EXPECT_LE(by_steps, 1);  // the one of the comment above, until grazing exits march faster
  EXPECT_EQ(acne, 0);
}

// A transmissive SDF solid (docs/scene-language.md: rays inside march by |distance|, the
// negated distance): rays refracted into an sdf sphere (index 1.5) from its surface, offset as
// the render offsets them, leave it where the analytic sphere says, within the band in which the
// march may stop (the tolerance over the cosine at the exit; Hart 1996, §2) and from the side
// inside (a back face).
TEST_P(SdfPacketTest, RefractedRaysLeaveAnSdfSphereWhereTheAnalyticSphereSays) {
  auto p = parse_scene("camera 0 0 20 0.5\nsdf\nsphere 0.5 -0.25 0.3 1.5\nend\n", "glass.scn");
  ASSERT_TRUE(p.ok());
  Scene s = std::move(p.scene);
  Bvh bvh = build_bvh_and_reorder(s, kWithWideNodes);
  Tracer tracer(s, bvh, TracerBackend::kPacket, GetParam().isa);
  const glm::dvec3 c(0.5, -0.25, 0.3);
  const double radius = 1.5, eta = 1 / 1.5;
  std::vector<Rayd> first = rays_at(s, 2000, 9), inside;
  std::vector<Hit> hits, in_hits;
  tracer.closest(first, hits);
  for (std::size_t i = 0; i < first.size(); ++i) {
    const Hit& h = hits[i];
    if (!h.hit() || !h.front_face) continue;
    glm::dvec3 d = normalize(first[i].d), n = h.surface.ng;
    double ci = -dot(d, n);
    if (ci < 0.1) continue;  // silhouettes aside
    glm::dvec3 wt = eta * d + (eta * ci - std::sqrt(1 - eta * eta * (1 - ci * ci))) * n;
    inside.push_back({offset_ray_origin(h.surface.p, hit_point_error(first[i], h.t), n, wt), wt});
  }
  tracer.closest(inside, in_hits);
  int far = 0, checked = 0;
  for (std::size_t i = 0; i < inside.size(); ++i) {
    const Rayd& r = inside[i];
    glm::dvec3 oc = r.o - c;
    double b = dot(oc, r.d), t_exit = -b + std::sqrt(b * b - (dot(oc, oc) - radius * radius));
    double cos_exit = dot(r.d, normalize(r.at(t_exit) - c));
    double o = std::max({std::abs(r.o.x), std::abs(r.o.y), std::abs(r.o.z)});
    if (cos_exit < 0.1) continue;  // a grazing exit: the band is wide, and total reflection near
    ++checked;
    double band = 2 * sdf_tolerance(t_exit, o) / cos_exit;
    const Hit& h = in_hits[i];
    bool ok = h.hit() && !h.front_face && std::abs(h.t - t_exit) <= band;
    far += !ok;
    EXPECT_TRUE(ok) << i << " t " << h.t << " analytic " << t_exit << " band " << band;
  }
  EXPECT_GT(checked, 300);
  EXPECT_EQ(far, 0);
}

// Over-relaxed steps (sdf_packet.h; Keinert et al. 2014) against plain ones on the pixels of
// scenes/sdf.scn, each block marched by the kernel at SSE4.2 (the test binary's baseline; the
// tests above run it at every ISA through the tracer): the same rays hit, within the band of two
// marches, and the steps per march are printed for each ω (bench/README.md, "SDF blocks").
TEST(SdfMarch, OverRelaxedStepsFindTheSameSurfacesInFewerSteps) {
  using A = xsimd::sse4_2;
  using F = simd::Floats<A>;
  constexpr int W = simd::kWidth<A>;
  auto p = load_scene_file(testing::source_path("scenes/sdf.scn"));
  ASSERT_TRUE(p.ok());
  const SdfTable& s = p.scene.table<Sdf>();
  Camera cam = Camera::from_scene(p.scene);
  std::vector<Rayd> rays;
  for (uint32_t y = 0; y < cam.height; ++y)
    for (uint32_t x = 0; x < cam.width; ++x)
      rays.push_back(round_to_float(cam.ray_through(x + 0.5, y + 0.5)));
  const float omegas[] = {1.0f, kSdfOverRelaxation, 1.4f, 1.6f, 1.8f};
  uint64_t steps[5] = {}, marches[5] = {}, out_of_steps[5] = {};
  int differ = 0, hits = 0;
  for (uint32_t row = 0; row < s.size(); ++row) {
    const detail::SdfBlockLanes blk(s, s.block[row]);
    for (std::size_t i = 0; i < rays.size(); i += W) {
      alignas(64) float col[7][W];
      for (int k = 0; k < W; ++k) {
        const Rayd& r = rays[std::min(i + k, rays.size() - 1)];
        float v[7] = {float(r.o.x), float(r.o.y), float(r.o.z), float(r.d.x),
                      float(r.d.y), float(r.d.z), float(r.tmin)};
        for (int c = 0; c < 7; ++c)
          col[c][k] = v[c];
      }
      RayPacket<A> r;
      r.ox = simd::load<A>(col[0]), r.oy = simd::load<A>(col[1]), r.oz = simd::load<A>(col[2]);
      r.dx = simd::load<A>(col[3]), r.dy = simd::load<A>(col[4]), r.dz = simd::load<A>(col[5]);
      r.inv_dx = F(1.0f) / r.dx, r.inv_dy = F(1.0f) / r.dy, r.inv_dz = F(1.0f) / r.dz;
      r.tmin = simd::load<A>(col[6]);
      const simd::Mask<A> lanes =
          simd::first_lanes<A>(int(std::min<std::size_t>(W, rays.size() - i)));
      const F tmax(std::numeric_limits<float>::infinity());
      alignas(64) float t[5][W];
      uint32_t hit[5];
      for (int w = 0; w < 5; ++w) {
        auto m = detail::sdf_march_lanes<A>(s, blk, row, lanes, r, tmax, omegas[w]);
        steps[w] += m.steps, marches[w] += m.marches, out_of_steps[w] += m.out_of_steps;
        simd::store<A>(t[w], m.t);
        hit[w] = simd::bits<A>(m.hit);
      }
      for (int k = 0; k < W && i + k < rays.size(); ++k) {
        const Rayd& ray = rays[i + k];
        hits += (hit[0] >> k) & 1u;
        for (int w = 1; w < 5; ++w) {
          if (((hit[w] ^ hit[0]) >> k) & 1u) {
            ++differ;  // a silhouette: the ray passes within the tolerance
            continue;
          }
          if (!((hit[0] >> k) & 1u)) continue;
          Surface n = surface_ref(s, s.leaf_begin[s.block[row]], ray, t[0][k]);
          EXPECT_NEAR(t[w][k], t[0][k], march_band(ray, t[0][k], std::abs(dot(n.ng, ray.d))))
              << row << " " << i + k << " " << omegas[w];
        }
      }
    }
  }
  for (int w = 0; w < 5; ++w)
    std::printf("[ march    ] omega %.1f: %.2f steps per march (%llu marches, %llu out of steps)\n",
                omegas[w], double(steps[w]) / double(marches[w]), (unsigned long long)marches[w],
                (unsigned long long)out_of_steps[w]);
  EXPECT_GT(hits, 5000);
  EXPECT_LT(differ, hits / 500);
  EXPECT_LT(steps[1], steps[0]);
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
