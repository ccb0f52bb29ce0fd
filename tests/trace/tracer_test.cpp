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
    glm::dvec3 o{};
    for (int k = 0; k < 3; ++k) {
      double u = rng.uniform();
      o[k] = b.lo[k] + (b.hi[k] - b.lo[k]) * u;
    }
    double u1 = rng.uniform(), u2 = rng.uniform();
    glm::dvec3 d = sample_uniform_sphere(u1, u2);
    if (i % 4 == 0 && tris.size() > 0) {
      auto row = uint32_t(std::min<double>(u1 * double(tris.size()), double(tris.size() - 1)));
      glm::dvec3 c =
          (glm::dvec3(tris.p0(row)) + glm::dvec3(tris.p1(row)) + glm::dvec3(tris.p2(row))) / 3.0;
      d = normalize(c - o);
    }
    rays.push_back({o, d});
  }
  // Times of a generator of their own (the rays are what they were), for the moving spheres.
  Rng times(6);
  for (Rayd& r : rays)
    r.time = std::min(times.uniform(), 0x1.fffffffffffffp-1);
  return rays;
}

// Moving spheres in the course scene's room (one standing still), so that every tracer's
// answers cover them at the rays' times.
void add_moving_spheres(Scene& scene) {
  MovingSphereTable& t = scene.table<MovingSphere>();
  for (int i = 0; i < 12; ++i) {
    double x = 1 + i % 4 * 3.0, y = 1 + i / 4 * 4.0, z = 1 + i % 3 * 2.5;
    double dx = i % 6 == 0 ? 0 : 2.5, dz = i % 2 ? 1.5 : -1.0;
    t.append(std::array<double, 7>{x, y, z, x + dx, y, z + dz, 0.4 + 0.1 * (i % 3)}, 0);
  }
}

// CSG blocks in the room too (bitten spheres, drilled boxes), so that every tracer's answers
// cover them: their hits name leaves, and their subtracted leaves' normals are turned around.
void add_csg_blocks(Scene& scene) {
  for (int i = 0; i < 3; ++i) {
    double x = 2.5 + 3 * i, y = 7, z = 3.5;
    CsgTable draft;
    if (i % 2 == 0)
      draft.add_leaf<Sphere>(std::array<double, 4>{x, y, z, 0.7}, 0);
    else
      draft.add_leaf<Box>(std::array<double, 6>{x - 0.6, y - 0.6, z - 0.6, 1.2, 1.2, 1.2}, 0);
    draft.add_leaf<Cylinder>(std::array<double, 7>{x, y - 1, z + 0.2, 0, 2, 0, 0.3}, 0);
    draft.add_code(kCsgDifference);
    scene.table<Csg>().append_block(draft);
  }
}

// SDF blocks too (tori, spheres melted by a smooth union), in front of the CSG blocks: their
// hits name the leaf nearest the point, their surfaces come from the distance's gradient.
void add_sdf_blocks(Scene& scene) {
  SdfTable& t = scene.table<Sdf>();
  for (int i = 0; i < 3; ++i) {
    double x = 2.5 + 3 * i, y = 5.5, z = 3.5;
    t.begin_block();
    if (i % 2 == 0) {
      t.add_torus(std::array<double, 8>{x, y, z, 0, 1, 0.3, 0.5, 0.2}, 0);
    } else {
      t.add_leaf<Sphere>(std::array<double, 4>{x - 0.3, y, z, 0.4}, 0);
      t.add_leaf<Sphere>(std::array<double, 4>{x + 0.3, y, z, 0.4}, 0);
      t.add_code(kSdfSmoothUnion, 0.3f);
    }
    t.end_block();
  }
}

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

// `check` on the course scene's random rays with every tracer: the packet tracer at every
// instruction set on `count` rays, the double references on `reference_count` of them (slow).
// With moving spheres added (add_moving_spheres); `change` may alter the scene further.
template <class Check, class Change = void (*)(Scene&)>
void with_every_tracer(
    int count, std::size_t reference_count, Check check, Change change = [](Scene&) {}) {
  ParsedScene parsed = load_builtin_scene();
  ASSERT_TRUE(parsed.ok());
  add_moving_spheres(parsed.scene);
  add_csg_blocks(parsed.scene);
  add_sdf_blocks(parsed.scene);
  change(parsed.scene);
  Bvh bvh = build_bvh_and_reorder(parsed.scene);
  const Scene& scene = parsed.scene;
  std::vector<Rayd> rays = random_rays(scene, bvh, count);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(isa_name(isa));
    check(Tracer(scene, bvh, TracerBackend::kPacket, isa), rays);
  }
  rays.resize(reference_count);
  check(Tracer(scene, bvh, TracerBackend::kBvh), rays);
  check(Tracer(scene, bvh, TracerBackend::kScalar), rays);
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

// What the columns hold for a hit (Tracer::surfaces): the packet tracer's boxes, spheres and
// triangles in float lanes, with their bounds — the same steps' scalar float instance, bit for
// bit; every other surface complete()'s, rounded to float, with float_hit_point_bound computed
// in double and rounded.
struct Columns {
  glm::vec3 p, ng, ns, error;
  double cos_ns;
  bool front, in_float;
};

Columns expected_columns(const Tracer& tracer, const Rayf& ray, const Hit& hit) {
  const Scene& scene = tracer.scene();
  const float t = float(hit.t);
  auto from_float = [&](const glm::vec3& p, const glm::vec3& n, const glm::vec3& error) {
    const float c = ray.d.x * n.x + ray.d.y * n.y + ray.d.z * n.z;
    return Columns{p, n, n, error, c, c < 0, true};
  };
  if (tracer.backend() == TracerBackend::kPacket && hit.prim.tag() == tag_of<Box>) {
    const BoxTable& b = scene.table<Box>();
    const glm::vec3 lo = b.lo(hit.prim.row()), hi = b.hi(hit.prim.row());
    const BoxSurface<glm::vec3> s = box_surface<float>(lo, hi, ray.o, ray.d, t);
    return from_float(s.p, s.n, box_point_bound<float>(lo, hi, ray.o, ray.d, t, s));
  }
  if (tracer.backend() == TracerBackend::kPacket && hit.prim.tag() == tag_of<Sphere>) {
    const SphereTable& sp = scene.table<Sphere>();
    const uint32_t i = hit.prim.row();
    const SphereSurface<glm::vec3> s =
        sphere_surface<float>(sp.center(i), sp.r[i], ray.o, ray.d, t);
    return from_float(s.p, s.n, sphere_point_bound<float>(s.p, s.offset));
  }
  if (tracer.backend() == TracerBackend::kPacket && hit.prim.tag() == tag_of<Triangle>) {
    const TriangleTable& tri = scene.table<Triangle>();
    const uint32_t i = hit.prim.row();
    const std::array<glm::vec3, 3> v{tri.p0(i), tri.p1(i), tri.p2(i)},
        vn{tri.n0(i), tri.n1(i), tri.n2(i)};
    const TriangleSurface<glm::vec3> s = triangle_surface<float>(v, vn, ray.o, ray.d, t);
    const float c = ray.d.x * s.ns.x + ray.d.y * s.ns.y + ray.d.z * s.ns.z;
    const float g = ray.d.x * s.ng.x + ray.d.y * s.ng.y + ray.d.z * s.ng.z;
    return {s.p, s.ng, s.ns, triangle_point_bound<float>(s, v, ray.o, ray.d, t), c, g < 0, true};
  }
  const Rayd rd = ray_cast<double>(ray);
  Hit h = hit;
  tracer.complete(rd, h);
  const Surface& s = h.surface;
  glm::dvec3 error = float_hit_point_bound<double>(rd.o, rd.d, hit.t, s.p);
  if (hit.prim.tag() == tag_of<Triangle>)  // the references' triangles
    error += triangle_vertex_bound(scene.table<Triangle>(), hit.prim.row());
  return {glm::vec3(s.p),
          glm::vec3(s.ng),
          glm::vec3(s.ns),
          glm::vec3(error),
          dot(s.ns, rd.d),
          h.front_face,
          false};
}

// The hits closest() gives as columns (HitStream) as records, prim and t alone.
std::vector<Hit> records_of(const HitStream& columns) {
  std::vector<Hit> hits(columns.t.size());
  for (std::size_t i = 0; i < hits.size(); ++i)
    hits[i].t = columns.t[i], hits[i].prim = PrimRef::from_bits(columns.prim[i]);
  return hits;
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

// surfaces() writes complete()'s surfaces into columns, for hits given as columns (prim and t
// alone: for the references, the surface at the float t). The request lists the hits
// backward, every third skipped, twice over, so row r is not hit r and the kinds are
// interleaved; then every hit again, kind by kind, so that each kind's rows come in long runs
// of different hits (the lanes store a whole run at once: a lane stored in the wrong row shows).
// Every kind hit, unless the scene has none of some (the kinds without spheres and boxes).
void expect_surface_columns_are_completes(const Tracer& tracer, const std::vector<Rayd>& rays) {
  const RayStream stream = RayStream::from(rays);
  TraceScratch scratch;
  HitStream columns;
  tracer.closest(stream, columns, scratch);
  const std::vector<Hit> hits = records_of(columns);
  const double nan = std::nan("");
  std::vector<uint32_t> request;
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = hits.size(); i-- > 0;) {
      if (!hits[i].hit() || i % 3 == 0) continue;
      request.push_back(uint32_t(i));
    }
  // A third pass lists each kind's hits together, after an odd number of rows: long runs at
  // every lane width, starting off the lanes' alignment.
  request.push_back(request.front());
  for (std::size_t kind = 0; kind < kPrimKindCount; ++kind)
    for (std::size_t i = 0; i < hits.size(); ++i)
      if (hits[i].hit() && std::size_t(hits[i].prim.tag()) == kind) request.push_back(uint32_t(i));
  // The request ends in a part batch of the float lanes' kinds at every width (its length 5
  // more than a multiple of 16: the last batch holds 5 rows of 8 or 16, 1 of 4), which the
  // lanes store row by row.
  std::vector<uint32_t> float_kinds;
  for (std::size_t i = 0; i < hits.size(); ++i) {
    const PrimTag tag = hits[i].prim.tag();
    if (hits[i].hit() && (tag == tag_of<Sphere> || tag == tag_of<Box> || tag == tag_of<Triangle>))
      float_kinds.push_back(uint32_t(i));
  }
  for (std::size_t k = 0; !float_kinds.empty() && (k < 5 || request.size() % 16 != 5); ++k)
    request.push_back(float_kinds[k % float_kinds.size()]);
  const std::size_t n = request.size();
  std::vector<double> cos_ns(n);
  std::vector<float> p[3], ng[3], ns[3], error[3];
  std::vector<uint8_t> front(n, 2);
  for (int k = 0; k < 3; ++k)
    p[k].assign(n, nan), ng[k].assign(n, nan), ns[k].assign(n, nan), error[k].assign(n, nan);
  const SurfaceColumns out{p[0].data(),   p[1].data(),     p[2].data(),     ng[0].data(),
                           ng[1].data(),  ng[2].data(),    ns[0].data(),    ns[1].data(),
                           ns[2].data(),  error[0].data(), error[1].data(), error[2].data(),
                           cos_ns.data(), front.data()};
  tracer.surfaces(stream, columns, request, out, scratch);
  int back = 0, smooth = 0, kinds[kPrimKindCount] = {}, in_float = 0;
  for (std::size_t r = 0; r < n; ++r) {
    const Hit& hit = hits[request[r]];
    const Columns want = expected_columns(tracer, stream.get(request[r]), hit);
    auto row = [&](const std::vector<float>* c) { return glm::vec3(c[0][r], c[1][r], c[2][r]); };
    ASSERT_TRUE(same_bits(want.p, row(p)) && same_bits(want.ng, row(ng)) &&
                same_bits(want.ns, row(ns)) && same_bits(want.error, row(error)))
        << "row " << r << " kind " << int(hit.prim.tag());
    ASSERT_EQ(std::memcmp(&want.cos_ns, &cos_ns[r], sizeof(double)), 0) << "row " << r;
    ASSERT_EQ(front[r], want.front ? 1 : 0) << "row " << r;
    back += !want.front;
    smooth += !same_bits(want.ns, want.ng);
    in_float += want.in_float;
    ++kinds[std::size_t(hit.prim.tag())];
  }
  const Scene& scene = tracer.scene();
  const bool in_lanes =
      scene.table<Sphere>().size() + scene.table<Box>().size() + scene.table<Triangle>().size() !=
      0;
  if (tracer.backend() == TracerBackend::kPacket && in_lanes) {
    EXPECT_GT(in_float, int(n / 10));
  }
  EXPECT_GT(back, int(n / 50));
  EXPECT_GT(smooth, int(n / 100));  // interpolated normals: the two normals' columns differ
  PrimKinds::for_each([&](auto kind) {
    if (scene.table<decltype(kind)>().size() == 0) return;
    EXPECT_GT(kinds[kind_index<decltype(kind)>()], 0) << "no hit on " << decltype(kind)::name;
  });
}

// The course scene's triangles are flat (their vertex normals are the face's): bent, each
// vertex's every component its own way, so that the shading normal differs from the geometric
// one and a lane reading one vertex's column for another's shows.
void bend_vertex_normals(Scene& scene) {
  TriangleTable& t = scene.table<Triangle>();
  for (std::size_t i = 0; i < t.size(); ++i) {
    t.n0x[i] += 0.25f, t.n0y[i] += 0.10f, t.n0z[i] -= 0.15f;
    t.n1x[i] -= 0.20f, t.n1y[i] -= 0.25f, t.n1z[i] += 0.05f;
    t.n2x[i] += 0.10f, t.n2y[i] -= 0.20f, t.n2z[i] += 0.25f;
  }
}

TEST(Tracer, SurfaceColumnsAreCompletesSurfaces) {
  with_every_tracer(4000, 400, expect_surface_columns_are_completes, bend_vertex_normals);
}

// The float surfaces read a short table (the course scene's handful of spheres and boxes) by
// register permutes and a long one by gathers (simd/lane_lookup.h): with forty more small
// spheres and boxes about the room, each table is longer than two registers at every width.
void add_spheres_and_boxes(Scene& scene) {
  bend_vertex_normals(scene);
  for (int i = 0; i < 40; ++i) {
    const double x = 1 + i % 8 * 1.5, y = 1 + i / 8 * 1.5, z = 2 + i % 5;
    ASSERT_FALSE(scene.table<Sphere>().append(std::array<double, 4>{x, y, z, 0.3}, 0));
    ASSERT_FALSE(
        scene.table<Box>().append(std::array<double, 6>{x + 0.5, y, z - 1, 0.4, 0.5, 0.6}, 0));
  }
}

TEST(Tracer, SurfaceColumnsAreCompletesSurfacesInLongTables) {
  with_every_tracer(4000, 400, expect_surface_columns_are_completes, add_spheres_and_boxes);
}

// Without spheres or boxes the float surfaces' pass reads nothing and hands every row on.
TEST(Tracer, SurfaceColumnsAreCompletesSurfacesWithoutSpheresOrBoxes) {
  with_every_tracer(4000, 400, expect_surface_columns_are_completes, [](Scene& scene) {
    bend_vertex_normals(scene);
    std::apply([](auto&... c) { (c.clear(), ...); }, scene.table<Sphere>().columns());
    std::apply([](auto&... c) { (c.clear(), ...); }, scene.table<Box>().columns());
    std::erase_if(scene.lights, [](PrimRef p) { return p.tag() != tag_of<Triangle>; });
  });
}

}  // namespace
}  // namespace raylane
