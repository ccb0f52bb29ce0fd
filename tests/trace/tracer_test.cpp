// The Tracer's batch answers against its one-hit-at-a-time ones: closest() fills surfaces kind
// by kind, which must be complete()'s surfaces exactly, and occluded() must say whether the
// closest hit lies inside each ray's interval.
#include "raylane/trace/tracer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "raylane/core/ray_offset.h"
#include "raylane/core/warps.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/scene/parser.h"
#include "support/same_bits.h"
#include "trace/tracer_scenes.h"

namespace raylane {
namespace {

using testing::add_csg_blocks;
using testing::add_moving_spheres;
using testing::add_sdf_blocks;
using testing::random_rays;
using testing::records_of;
using testing::with_every_tracer;

using testing::same_bits;  // support/same_bits.h

// At every instruction set the CPU has: the batch computes spheres', boxes' and cylinders'
// surfaces in double lanes of that width (SimdTracer::surfaces), one-by-one complete() in scalar
// double (surface_ref).
void expect_batch_answers_are_one_by_one(const Scene& scene, const Bvh& bvh, Isa isa) {
  Tracer tracer(scene, bvh, TracerBackend::kPacket, isa);
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
  add_moving_spheres(parsed.scene);
  add_csg_blocks(parsed.scene);
  add_sdf_blocks(parsed.scene);
  Bvh bvh = build_bvh_and_reorder(parsed.scene);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(isa_name(isa));
    expect_batch_answers_are_one_by_one(parsed.scene, bvh, isa);
  }
}

// occluded() against the tracer's own closest(): for a ray whose closest hit is A at t1 and
// next hit (past t1) B at t2,
//  - unaimed, tmax just short of t1: clear; just past t1: blocked;
//  - aimed at A, tmax just past t1: clear (A does not block; nothing is before it);
//  - aimed at B, tmax just past t2: blocked by A, unless B is A itself (a solid's far side:
//    the aim's first hit ends the segment).
// Aimed cases are left out where the ray meets two surfaces within 1e-5 of t1 or t2 (surfaces
// that touch, as the course scene's walls do: on a tie either may be found first).
struct OcclusionCase {
  Rayd ray;
  PrimRef aim;
  uint8_t blocked;
  bool far_side = false;  // aimed at the far side of the solid the ray meets first
};

// How many primitives the ray meets within a relative `window` of t (double references).
int surfaces_near(const Scene& scene, const Rayd& ray, double t, double window) {
  int n = 0;
  PrimKinds::for_each([&](auto kind) {
    const auto& table = scene.table<decltype(kind)>();
    for (uint32_t row = 0; row < table.size(); ++row) {
      double u = intersect_ref(table, row, {ray.o, ray.d, t * (1 - window), t * (1 + window)});
      n += u < t * (1 + window);
    }
  });
  return n;
}

std::vector<OcclusionCase> occlusion_cases(const Tracer& tracer, const std::vector<Rayd>& rays) {
  std::vector<Hit> first, next;
  tracer.closest(rays, first);
  std::vector<Rayd> beyond = rays;
  for (std::size_t i = 0; i < rays.size(); ++i)
    beyond[i].tmin = first[i].hit() ? first[i].t : 0;
  tracer.closest(beyond, next);
  std::vector<OcclusionCase> cases;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    Rayd r = rays[i];
    const Hit &a = first[i], &b = next[i];
    if (!a.hit()) {
      cases.push_back({r, PrimRef::invalid(), 0});
      continue;
    }
    r.tmax = a.t * (1 - 1e-3), cases.push_back({r, PrimRef::invalid(), 0});
    r.tmax = a.t * (1 + 1e-3), cases.push_back({r, PrimRef::invalid(), 1});
    if (b.hit() && b.t < a.t * (1 + 1e-5)) continue;
    if (surfaces_near(tracer.scene(), r, a.t, 1e-5) > 1) continue;
    r.tmax = a.t * (1 + 1e-6), cases.push_back({r, a.prim, 0});
    if (!b.hit() || surfaces_near(tracer.scene(), r, b.t, 1e-5) > 1) continue;
    r.tmax = b.t * (1 + 1e-6);
    cases.push_back({r, b.prim, uint8_t(b.prim != a.prim), b.prim == a.prim});
  }
  return cases;
}

void expect_occluded_answers(const Tracer& tracer, const std::vector<Rayd>& rays) {
  std::vector<OcclusionCase> cases = occlusion_cases(tracer, rays);
  std::vector<Rayd> shadow;
  std::vector<PrimRef> aims;
  int aimed_clear = 0, aimed_blocked = 0, far_side = 0;
  for (const OcclusionCase& c : cases) {
    shadow.push_back(c.ray), aims.push_back(c.aim);
    aimed_clear += c.aim.valid() && !c.blocked;
    aimed_blocked += c.aim.valid() && c.blocked;
    far_side += c.far_side;
  }
  std::vector<uint8_t> blocked;
  TraceScratch scratch;
  tracer.occluded(shadow, aims, blocked, scratch);
  ASSERT_EQ(blocked.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    ASSERT_EQ(blocked[i], cases[i].blocked)
        << "case " << i << " aim " << cases[i].aim.bits() << " tmax " << cases[i].ray.tmax;
  }
  // Every kind of case occurs (the far sides of solids among the aimed clear ones).
  EXPECT_GT(aimed_clear, int(rays.size() / 4));
  EXPECT_GT(aimed_blocked, int(rays.size() / 8));
  EXPECT_GT(far_side, 10);
  // Without aims, the same rays' answers ignore them: an aim-less call on the aimed cases.
  std::vector<uint8_t> plain;
  tracer.occluded(shadow, {}, plain, scratch);
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (cases[i].aim.valid()) {
      ASSERT_EQ(plain[i], 1) << "case " << i;
    }
}

TEST(Tracer, OccludedAnswersWithAndWithoutAims) {
  with_every_tracer(4000, 500, expect_occluded_answers);
}

// The float-stream entry points (the render's) answer as the double ones do for the same rays
// widened from float: the packet tracer sees the same float rays either way, and the
// references trace the widened rays. The stream may be the scratch's own.
void expect_streams_answer_as_rays(const Tracer& tracer, const std::vector<Rayd>& given) {
  std::vector<Rayd> rays;
  for (const Rayd& r : given)
    rays.push_back(ray_cast<double>(ray_cast<float>(r)));
  std::vector<OcclusionCase> cases = occlusion_cases(tracer, rays);
  std::vector<Rayd> shadow;
  std::vector<PrimRef> aims;
  RayStream stream;
  for (OcclusionCase& c : cases) {
    if (shadow.size() % 3 == 0) c.ray.tmin = std::isinf(c.ray.tmax) ? 1.0 : c.ray.tmax / 2;
    shadow.push_back(c.ray), aims.push_back(c.aim);
    stream.resize(stream.size() + 1);
    stream.set(stream.size() - 1, ray_cast<float>(c.ray));
    stream.aim.push_back(c.aim.bits());
    stream.time.push_back(float(c.ray.time));
  }
  TraceScratch scratch;
  std::vector<uint8_t> want, got;
  tracer.occluded(shadow, aims, want, scratch);
  tracer.occluded(stream, got, scratch);
  ASSERT_EQ(got, want);
  EXPECT_GT(std::count(got.begin(), got.end(), 1), int(rays.size() / 8));

  std::vector<Hit> hits_want, hits_got;
  tracer.closest(shadow, hits_want);
  scratch.rays = stream;  // the stream is the scratch's own, its aim column still set
  tracer.closest(scratch.rays, hits_got, stream.size(), scratch);
  ASSERT_EQ(hits_got.size(), hits_want.size());
  int hit = 0;
  for (std::size_t i = 0; i < hits_want.size(); ++i) {
    const Hit &a = hits_want[i], &b = hits_got[i];
    ASSERT_EQ(a.prim, b.prim) << "ray " << i;
    if (!a.hit()) continue;
    ++hit;
    ASSERT_EQ(a.t, b.t) << "ray " << i;
    ASSERT_TRUE(same_bits(a.surface.p, b.surface.p) && same_bits(a.surface.ng, b.surface.ng) &&
                same_bits(a.surface.ns, b.surface.ns) && a.front_face == b.front_face)
        << "ray " << i;
  }
  EXPECT_GT(hit, int(rays.size() / 4));
}

TEST(Tracer, FloatStreamsAnswerAsTheirWidenedRays) {
  with_every_tracer(2000, 300, expect_streams_answer_as_rays);
}

// closest() as columns gives each ray the primitive of its record and the record's t rounded
// to float (the packet tracer's exactly: its t is a float).
void expect_hit_columns_are_the_records(const Tracer& tracer, const std::vector<Rayd>& rays) {
  const RayStream stream = RayStream::from(rays);
  TraceScratch scratch;
  std::vector<Hit> records;
  HitStream columns;
  tracer.closest(stream, records, 0, scratch);
  tracer.closest(stream, columns, scratch);
  ASSERT_EQ(columns.t.size(), rays.size());
  ASSERT_EQ(columns.prim.size(), rays.size());
  int hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    ASSERT_EQ(columns.prim[i], records[i].prim.bits()) << "ray " << i;
    ASSERT_TRUE(same_bits(columns.t[i], float(records[i].t))) << "ray " << i;
    if (tracer.backend() == TracerBackend::kPacket) {
      ASSERT_EQ(double(columns.t[i]), records[i].t);
    }
    hits += records[i].hit();
  }
  EXPECT_GT(hits, int(rays.size() / 4));
}

TEST(Tracer, HitColumnsAreTheRecordsPrimAndT) {
  with_every_tracer(2000, 300, expect_hit_columns_are_the_records);
}

}  // namespace
}  // namespace raylane
