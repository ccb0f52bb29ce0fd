// The Tracer's batch answers against its one-hit-at-a-time ones: closest() fills surfaces kind
// by kind, which must be complete()'s surfaces exactly, and front_face() must be the facing
// complete() finds (it skips the surface for spheres).
#include "raylane/trace/tracer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "raylane/core/warps.h"
#include "raylane/render/rng.h"
#include "raylane/scene/parser.h"

namespace raylane {
namespace {

// Rays from random points of the course scene's room (some inside its solids, so back faces
// are met too): three in four in uniform directions, one in four toward a random triangle's
// centroid (the letters are small: uniform directions alone may miss them).
std::vector<Rayd> random_rays(const Scene& scene, const Bvh& bvh, int count) {
  Rng rng(5);
  Bounds3f b = bvh.nodes[0].bounds();
  const TriangleTable& tris = scene.table<Triangle>();
  std::vector<Rayd> rays;
  for (int i = 0; i < count; ++i) {
    Vec3d o;
    for (int k = 0; k < 3; ++k) {
      double u = rng.uniform();
      o[k] = b.lo[k] + (b.hi[k] - b.lo[k]) * u;
    }
    double u1 = rng.uniform(), u2 = rng.uniform();
    Vec3d d = sample_uniform_sphere(u1, u2);
    if (i % 4 == 0 && tris.size() > 0) {
      auto row = uint32_t(std::min<double>(u1 * double(tris.size()), double(tris.size() - 1)));
      Vec3d c = (Vec3d(tris.p0(row)) + Vec3d(tris.p1(row)) + Vec3d(tris.p2(row))) / 3.0;
      d = normalize(c - o);
    }
    rays.push_back({o, d});
  }
  return rays;
}

bool same_bits(const Vec3d& a, const Vec3d& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// At every instruction set the CPU has: the batch computes spheres', boxes' and cylinders'
// surfaces in double lanes of that width (SimdTracer::surfaces), one-by-one complete() in scalar
// double (surface_ref).
void expect_batch_answers_are_one_by_one(const Scene& scene, const Bvh& bvh, Isa isa) {
  Tracer tracer(scene, bvh, TracerKind::kPacket, isa);
  std::vector<Rayd> rays = random_rays(scene, bvh, 20000);
  std::vector<Hit> hits;
  tracer.closest(rays, hits);
  int back = 0, kinds[kPrimKindCount] = {};
  for (std::size_t i = 0; i < rays.size(); ++i) {
    if (!hits[i].hit()) continue;
    Hit one = hits[i];
    one.surface = {};
    tracer.complete(rays[i], one);
    ASSERT_TRUE(same_bits(one.surface.p, hits[i].surface.p) &&
                same_bits(one.surface.ng, hits[i].surface.ng) &&
                same_bits(one.surface.ns, hits[i].surface.ns))
        << "ray " << i << " kind " << int(hits[i].prim.tag()) << ": p " << one.surface.p.x << " "
        << hits[i].surface.p.x << ", ng " << one.surface.ng.x << " " << hits[i].surface.ng.x;
    ASSERT_EQ(one.front_face, hits[i].front_face) << "ray " << i;
    // front_face() may differ only where the ray grazes the surface, its cosine within
    // rounding of 0 (the sphere's shortcut leaves out the normalisation).
    if (std::abs(dot(rays[i].d, one.surface.ng)) > 1e-12) {
      ASSERT_EQ(tracer.front_face(rays[i], hits[i]), one.front_face) << "ray " << i;
    }
    back += !one.front_face;
    ++kinds[std::size_t(hits[i].prim.tag())];
  }
  EXPECT_GT(back, 100);
  for (std::size_t k = 0; k < kPrimKindCount; ++k)
    EXPECT_GT(kinds[k], 0) << "no hit on kind " << k;
}

TEST(Tracer, BatchSurfacesAndFacingAreTheOneByOneAnswers) {
  ParsedScene parsed = load_builtin_scene();
  ASSERT_TRUE(parsed.ok());
  Bvh bvh = build_bvh(parsed.scene);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(isa_name(isa));
    expect_batch_answers_are_one_by_one(parsed.scene, bvh, isa);
  }
}

}  // namespace
}  // namespace raylane
