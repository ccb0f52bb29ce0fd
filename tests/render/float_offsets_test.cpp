// The accuracy contract's offsets at float: the render's hit points are float (Tracer::surfaces:
// spheres, boxes, triangles, cylinders and moving spheres in float lanes with their own bounds,
// sphere_point_bound, box_point_bound, triangle_point_bound, cylinder_point_bound and
// moving_sphere_point_bound; the other kinds rounded from double, float_hit_point_bound), and
// the rays a
// vertex spawns leave by offset_origin<float> (core/ray_offset.h; pbrt-v4 §6.8). On random scenes
// of every kind that the float surfaces cover, at every instruction set, at four scales (unit,
// far from the origin, tiny, huge):
// - the float point lies within its bound's projection on the normal of the true surface
//   (spheres, boxes, triangles, cylinders and moving spheres, measured in double from the
//   table's own float numbers);
// - a ray reflected off a front face never meets its own primitive again (acne), and one
//   continuing into the solid never meets its own primitive's front face (a leak: it started
//   outside). Convex primitives and planar triangles allow neither, whatever the scene holds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "raylane/core/ray_offset.h"
#include "raylane/core/strings.h"
#include "raylane/core/warps.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/trace/tracer.h"
#include "support/random_scene.h"

namespace raylane {
namespace {

using Vec = glm::vec3;

struct Scale {
  const char* name;
  double extent, size;
  glm::dvec3 offset;
};

// Far from the origin the offset grows with the coordinates (2^5 float roundoffs of |p|): there
// a primitive must stay wider than it, so the far scene keeps its smallest cylinders (radius
// 0.036) about 150 float ulps wide at |p| ≈ 2500. At 25000 they are 18 ulps wide, and 3 of 5063
// rays continuing into them met a cylinder's front face (1 with the double reference's offsets).
constexpr Scale kScales[] = {{"unit", 10, 0.6, {0, 0, 0}},
                             {"far", 10, 0.6, {1.5e3, -2.5e3, 4e2}},
                             {"tiny", 1e-3, 6e-5, {0, 0, 0}},
                             {"huge", 1e5, 6e3, {0, 0, 0}}};

// The float hits of a stream: the render's columns (point, geometric normal, facing).
struct FloatHits {
  HitStream hits;
  std::vector<uint32_t> rows;  // the rays that hit something
  std::vector<float> p[3], ng[3], ns[3], error[3];
  std::vector<double> cos_ns;
  std::vector<uint8_t> front;
  PrimRef prim(std::size_t i) const { return PrimRef::from_bits(hits.prim[i]); }  // ray i's
  Vec point(std::size_t r) const { return {p[0][r], p[1][r], p[2][r]}; }
  Vec normal(std::size_t r) const { return {ng[0][r], ng[1][r], ng[2][r]}; }
  Vec bound(std::size_t r) const { return {error[0][r], error[1][r], error[2][r]}; }
};

FloatHits trace_float(const Tracer& tracer, const RayStream& rays) {
  FloatHits f;
  TraceScratch scratch;
  tracer.closest(rays, f.hits, scratch);
  for (std::size_t i = 0; i < rays.size(); ++i)
    if (PrimRef::from_bits(f.hits.prim[i]).valid()) f.rows.push_back(uint32_t(i));
  const std::size_t n = f.rows.size();
  for (int k = 0; k < 3; ++k)
    f.p[k].resize(n), f.ng[k].resize(n), f.ns[k].resize(n), f.error[k].resize(n);
  f.cos_ns.resize(n), f.front.resize(n);
  const SurfaceColumns out{f.p[0].data(),   f.p[1].data(),     f.p[2].data(),     f.ng[0].data(),
                           f.ng[1].data(),  f.ng[2].data(),    f.ns[0].data(),    f.ns[1].data(),
                           f.ns[2].data(),  f.error[0].data(), f.error[1].data(), f.error[2].data(),
                           f.cos_ns.data(), f.front.data()};
  tracer.surfaces(rays, f.hits, f.rows, out, scratch);
  return f;
}

// How far the float point lies off the true surface of its primitive, in double (nan for a
// kind without a distance here).
double distance_off_surface(const Scene& scene, PrimRef prim, const glm::dvec3& p,
                            const glm::dvec3& n, double time) {
  const uint32_t i = prim.row();
  if (prim.tag() == tag_of<MovingSphere>) {  // about its centre at the ray's time
    const MovingSphereTable& s = scene.table<MovingSphere>();
    return std::abs(length(p - s.center_at(i, time)) - double(s.r[i]));
  }
  if (prim.tag() == tag_of<Sphere>) {
    const SphereTable& s = scene.table<Sphere>();
    return std::abs(length(p - glm::dvec3(s.cx[i], s.cy[i], s.cz[i])) - double(s.r[i]));
  }
  if (prim.tag() == tag_of<Triangle>) {
    const TriangleTable& t = scene.table<Triangle>();
    const glm::dvec3 a(t.p0(i)), b(t.p1(i)), c(t.p2(i));
    return std::abs(dot(p - a, normalize(cross(b - a, c - a))));
  }
  if (prim.tag() == tag_of<Box>) {  // the nearest of the six face planes
    const BoxTable& b = scene.table<Box>();
    const glm::dvec3 lo(b.lo(i)), hi(b.hi(i));
    double d = HUGE_VAL;
    for (int k = 0; k < 3; ++k)
      d = std::min({d, std::abs(p[k] - lo[k]), std::abs(p[k] - hi[k])});
    return d;
  }
  if (prim.tag() == tag_of<Cylinder>) {  // the reference's cylinder: base b, axis u·h in double
    // Off the part the normal names (a cap's plane or the side's round), as for a box's face.
    const CylinderTable& c = scene.table<Cylinder>();
    const glm::dvec3 axis = c.axis(i), u = normalize(axis), q = p - glm::dvec3(c.base(i));
    const double h = length(axis), z = dot(q, u), along = dot(n, u);
    if (std::abs(along) > 0.5) return along < 0 ? std::abs(z) : std::abs(z - h);
    return std::abs(length(q - z * u) - double(c.r[i]));
  }
  return std::nan("");
}

bool convex_or_planar(PrimTag tag) {
  return tag == tag_of<Sphere> || tag == tag_of<Box> || tag == tag_of<Cylinder> ||
         tag == tag_of<MovingSphere> || tag == tag_of<Triangle>;
}

struct Counts {
  int front_hits = 0, measured = 0, beyond_bound = 0, acne = 0, leaks = 0;
  int kinds[kPrimKindCount] = {};
};

void check_scale(const Scale& scale, Isa isa, Counts& n) {
  Scene scene = testing::random_scene(7, 300, scale.extent, scale.size, scale.offset);
  Bvh bvh = build_bvh_and_reorder(scene);
  const Tracer tracer(scene, bvh, TracerBackend::kPacket, isa);
  const RayStream rays =
      RayStream::from(testing::random_rays(8, 40000, scale.extent * 1.2, scale.offset));
  const FloatHits first = trace_float(tracer, rays);
  RayStream out, into;
  std::vector<PrimRef> own;
  for (std::size_t r = 0; r < first.rows.size(); ++r) {
    const uint32_t i = first.rows[r];
    const PrimRef prim = first.prim(i);
    if (!first.front[r] || !convex_or_planar(prim.tag())) continue;
    const Rayf ray = rays.get(i);
    const Vec p = first.point(r), ng = first.normal(r);
    const Vec err = first.bound(r);
    ++n.front_hits, ++n.kinds[std::size_t(prim.tag())];
    const double off =
        distance_off_surface(scene, prim, glm::dvec3(p), glm::dvec3(ng), double(ray.time));
    if (!std::isnan(off)) {
      ++n.measured;
      const double bound = dot(abs(glm::dvec3(ng)), glm::dvec3(err));
      n.beyond_bound += !(off <= bound);
    }
    const Vec reflected = ray.d - 2.0f * dot(ray.d, ng) * ng;
    const std::size_t k = out.size();
    out.resize(k + 1), into.resize(k + 1);
    if (!rays.time.empty()) out.time.push_back(ray.time), into.time.push_back(ray.time);
    out.set(k, {offset_origin<float>(p, err, ng, ng), reflected, 0, HUGE_VALF, ray.time});
    into.set(k, {offset_origin<float>(p, err, ng, -ng), ray.d, 0, HUGE_VALF, ray.time});
    own.push_back(prim);
  }
  const FloatHits o = trace_float(tracer, out), in = trace_float(tracer, into);
  for (std::size_t r = 0; r < o.rows.size(); ++r)
    n.acne += o.prim(o.rows[r]) == own[o.rows[r]];
  for (std::size_t r = 0; r < in.rows.size(); ++r)
    n.leaks += in.prim(in.rows[r]) == own[in.rows[r]] && in.front[r];
}

TEST(FloatOffsets, FloatHitPointsLieWithinTheirBoundAndSpawnedRaysNeitherLeakNorReHit) {
  for (Isa isa : supported_isas())
    for (const Scale& scale : kScales) {
      SCOPED_TRACE(cat(isa_name(isa), " ", scale.name));
      Counts n;
      check_scale(scale, isa, n);
      std::printf("[ %-8s ] %s: %d front hits, %d of %d beyond the bound, %d acne, %d leaks\n",
                  scale.name, std::string(isa_name(isa)).c_str(), n.front_hits, n.beyond_bound,
                  n.measured, n.acne, n.leaks);
      EXPECT_EQ(n.beyond_bound, 0);
      EXPECT_EQ(n.acne, 0);
      EXPECT_EQ(n.leaks, 0);
      EXPECT_GT(n.measured, 3000);
      for (PrimTag tag :
           {tag_of<Sphere>, tag_of<Box>, tag_of<Cylinder>, tag_of<MovingSphere>, tag_of<Triangle>})
        EXPECT_GT(n.kinds[std::size_t(tag)], 100) << "kind " << int(tag);
    }
}

// n rays from heights [lo, hi] above the plane y = 0 to points of it, both within |x|, |z| < half.
std::vector<Rayd> rays_onto_y0(uint64_t seed, int n, double half, double lo, double hi) {
  Rng rng(seed);
  auto across = [&] { return 2 * half * rng.uniform() - half; };
  std::vector<Rayd> rays;
  for (int i = 0; i < n; ++i) {
    glm::dvec3 o, to;  // one number at a time: argument order is unspecified
    o.x = across(), o.y = lo + (hi - lo) * rng.uniform(), o.z = across();
    to.x = across(), to.y = 0, to.z = across();
    rays.push_back({o, normalize(to - o)});
  }
  return rays;
}

// docs/hard-cases.md S2: a sphere of radius 1e5 as the ground, its top at y = 0, seen from
// 1 to 10 above within |x|, |z| < 10. Float resolves heights there only to ulp(1e5) = 0.0078, so
// the offset must scale with the radius (the sphere's bound: γ6 of n·r, about 0.036): no
// reflected ray may meet the ground again, and no ray continuing down may meet it from outside.
TEST(FloatOffsets, AHugeSphereAsGroundIsLeftByItsOwnBound) {
  Scene scene;
  scene.materials.push_back(Material{});
  scene.table<Sphere>().append(std::array<double, 4>{0, -1e5, 0, 1e5}, 0);
  Bvh bvh = build_bvh_and_reorder(scene);
  const RayStream rays = RayStream::from(rays_onto_y0(3, 40000, 10, 1, 10));
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    const Tracer tracer(scene, bvh, TracerBackend::kPacket, isa);
    const FloatHits first = trace_float(tracer, rays);
    RayStream out, into;
    for (std::size_t r = 0; r < first.rows.size(); ++r) {
      const Rayf ray = rays.get(first.rows[r]);
      const Vec p = first.point(r), ng = first.normal(r), err = first.bound(r);
      const std::size_t k = out.size();
      out.resize(k + 1), into.resize(k + 1);
      const Vec reflected = ray.d - 2.0f * dot(ray.d, ng) * ng;
      out.set(k, {offset_origin<float>(p, err, ng, ng), reflected, 0, HUGE_VALF, 0.5f});
      into.set(k, {offset_origin<float>(p, err, ng, -ng), ray.d, 0, HUGE_VALF, 0.5f});
    }
    const FloatHits o = trace_float(tracer, out), in = trace_float(tracer, into);
    int front_from_inside = 0;
    for (std::size_t r = 0; r < in.rows.size(); ++r)
      front_from_inside += in.front[r];
    std::printf(
        "[ ground   ] %s: %zu hits, %zu reflected rays re-hit, %d continuing rays "
        "meet its front\n",
        std::string(isa_name(isa)).c_str(), first.rows.size(), o.rows.size(), front_from_inside);
    EXPECT_GT(first.rows.size(), 39000u);
    EXPECT_EQ(o.rows.size(), 0u);
    EXPECT_EQ(front_from_inside, 0);
  }
}

// docs/hard-cases.md N5 at float: a box whose top face lies at y = 0 (the course scene's floor),
// hit from above; rays leave the hit points within the face's plane (direction y = +0 or −0),
// where a slab test's (0 − o)·(1/±0) is NaN for an origin exactly on the plane. The origin
// must leave the plane even though the face's coordinate is 0, so that no such ray meets its
// own box.
TEST(FloatOffsets, RaysAlongAFaceAtZeroDoNotMeetTheirOwnBox) {
  Scene scene;
  scene.materials.push_back(Material{});
  scene.table<Box>().append(std::array<double, 6>{-10, -1, -10, 20, 1, 20}, 0);
  Bvh bvh = build_bvh_and_reorder(scene);
  const RayStream rays = RayStream::from(rays_onto_y0(4, 20000, 8, 1, 5));
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    const Tracer tracer(scene, bvh, TracerBackend::kPacket, isa);
    const FloatHits first = trace_float(tracer, rays);
    RayStream along;
    for (std::size_t r = 0; r < first.rows.size(); ++r) {
      const Vec p = first.point(r), ng = first.normal(r), err = first.bound(r);
      const float phi = float(r) * 0.7f;
      const Vec d(std::cos(phi), r % 2 ? 0.0f : -0.0f, std::sin(phi));
      const std::size_t k = along.size();
      along.resize(k + 1);
      along.set(k, {offset_origin<float>(p, err, ng, ng), d, 0, HUGE_VALF, 0.5f});
    }
    const FloatHits a = trace_float(tracer, along);
    std::printf("[ face at 0 ] %s: %zu hits on the top, %zu rays along it meet the box\n",
                std::string(isa_name(isa)).c_str(), first.rows.size(), a.rows.size());
    EXPECT_GT(first.rows.size(), 19000u);
    EXPECT_EQ(a.rows.size(), 0u);
  }
}

// docs/hard-cases.md R2: a large tilted triangle pair (normal ∝ (1, 2, 3), vertices of magnitude
// 50 to 70) near the world origin, hit by rays that start 0.05 to 0.5 from points within 0.3 of
// the origin, as secondary rays do. The float kernel's own error grows with the vertices'
// magnitudes, not with |o| + |t·d|; a reflected ray must not meet the triangle it left.
struct LargeTriangles {
  Scene scene;
  Bvh bvh;
  glm::dvec3 n;
  std::vector<Rayd> near;
};

LargeTriangles large_triangles_near_the_origin() {
  LargeTriangles l;
  l.scene.materials.push_back(Material{});
  const glm::dvec3 n = l.n = normalize(glm::dvec3(1, 2, 3));
  const glm::dvec3 u = normalize(cross(n, glm::dvec3(1, 0, 0))), v = cross(n, u);
  auto at = [&](double a, double b) { return glm::vec3(u * a + v * b); };
  const std::array<glm::vec3, 3> t0{at(-60, -50), at(60, -45), at(-5, 70)};
  const std::array<glm::vec3, 3> t1{at(60, -45), at(55, 65), at(-5, 70)};
  const glm::vec3 fn(n);
  l.scene.table<Triangle>().append(t0, {fn, fn, fn}, 0);
  l.scene.table<Triangle>().append(t1, {fn, fn, fn}, 0);
  l.bvh = build_bvh_and_reorder(l.scene);
  Rng rng(5);
  for (int i = 0; i < 200000; ++i) {
    glm::dvec3 target;
    target.x = 0.6 * rng.uniform() - 0.3, target.y = 0.6 * rng.uniform() - 0.3;
    target.z = -(n.x * target.x + n.y * target.y) / n.z;  // on the plane through 0
    const double away = 0.05 + 0.45 * rng.uniform();
    glm::dvec3 off = sample_uniform_sphere(rng.uniform(), rng.uniform());
    if (dot(off, n) < 0.2) off = normalize(off + n);
    l.near.push_back({target + off * away, -off});
  }
  return l;
}

// R2 at float: the float points and bounds of Tracer::surfaces, offset_origin.
TEST(FloatOffsets, ALargeTriangleNearTheOriginIsNotHitAgain) {
  const LargeTriangles l = large_triangles_near_the_origin();
  const RayStream rays = RayStream::from(l.near);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    const Tracer tracer(l.scene, l.bvh, TracerBackend::kPacket, isa);
    const FloatHits first = trace_float(tracer, rays);
    RayStream out;
    std::vector<PrimRef> own;
    for (std::size_t r = 0; r < first.rows.size(); ++r) {
      const Rayf ray = rays.get(first.rows[r]);
      const Vec p = first.point(r), ng = first.normal(r), err = first.bound(r);
      const Vec side = dot(ray.d, ng) < 0 ? ng : -ng;
      const Vec reflected = ray.d - 2.0f * dot(ray.d, ng) * ng;
      const std::size_t k = out.size();
      out.resize(k + 1);
      out.set(k, {offset_origin<float>(p, err, ng, side), reflected, 0, HUGE_VALF, 0.5f});
      own.push_back(first.prim(first.rows[r]));
    }
    const FloatHits o = trace_float(tracer, out);
    int again = 0;
    for (uint32_t i : o.rows)
      again += o.prim(i) == own[i];
    std::printf("[ large tri ] %s: %zu hits, %d reflected rays meet their triangle again\n",
                std::string(isa_name(isa)).c_str(), first.rows.size(), again);
    EXPECT_GT(first.rows.size(), 190000u);
    EXPECT_EQ(again, 0);
  }
}

// R2 at double, as the double shading and the lit view spawn rays: the hit's double point and
// Tracer::hit_point_bound, offset_ray_origin. With hit_point_error alone, without the
// triangle's term, 25,427 (AVX2, AVX-512) and 28,492 (SSE4.2) of the 200,000 reflected rays met
// their triangle again.
TEST(DoubleOffsets, ALargeTriangleNearTheOriginIsNotHitAgain) {
  const LargeTriangles l = large_triangles_near_the_origin();
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    const Tracer tracer(l.scene, l.bvh, TracerBackend::kPacket, isa);
    std::vector<Hit> first, again_hits;
    tracer.closest(l.near, first);
    std::vector<Rayd> out;
    std::vector<PrimRef> own;
    for (std::size_t i = 0; i < first.size(); ++i) {
      const Hit& h = first[i];
      if (!h.hit()) continue;
      const Rayd ray = ray_cast<double>(ray_cast<float>(l.near[i]));  // the ray as traced
      const glm::dvec3 ng = h.surface.ng, side = dot(ray.d, ng) < 0 ? ng : -ng;
      const glm::dvec3 reflected = ray.d - 2.0 * dot(ray.d, ng) * ng;
      out.push_back(
          {offset_ray_origin(h.surface.p, tracer.hit_point_bound(ray, h), ng, side), reflected});
      own.push_back(h.prim);
    }
    tracer.closest(out, again_hits);
    int again = 0;
    for (std::size_t i = 0; i < out.size(); ++i)
      again += again_hits[i].prim == own[i];
    std::printf(
        "[ large tri, double ] %s: %zu hits, %d reflected rays meet their triangle "
        "again\n",
        std::string(isa_name(isa)).c_str(), out.size(), again);
    EXPECT_GT(out.size(), 190000u);
    EXPECT_EQ(again, 0);
  }
}

}  // namespace
}  // namespace raylane
