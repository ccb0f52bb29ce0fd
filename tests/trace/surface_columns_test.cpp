// The Tracer's surfaces as columns (Tracer::surfaces), the render's: against complete()'s
// surfaces one hit at a time, and, for the kinds the packet tracer computes in float lanes
// (spheres, boxes, triangles, cylinders, moving spheres), against the same steps' scalar float
// instance, bit for bit, with their error bounds.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <tuple>
#include <vector>

#include "raylane/core/ray_offset.h"
#include "raylane/trace/tracer.h"
#include "support/same_bits.h"
#include "trace/tracer_scenes.h"

namespace raylane {
namespace {

using testing::records_of;
using testing::same_bits;
using testing::with_every_tracer;

// What the columns hold for a hit (Tracer::surfaces): the packet tracer's boxes, spheres,
// triangles, cylinders and moving spheres in float lanes, with their bounds — the same steps'
// scalar float instance, bit for bit; every other surface complete()'s, rounded to float, with
// float_hit_point_bound computed in double and rounded.
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
  if (tracer.backend() == TracerBackend::kPacket && hit.prim.tag() == tag_of<Cylinder>) {
    const CylinderTable& c = scene.table<Cylinder>();
    const uint32_t i = hit.prim.row();
    const glm::vec3 u = c.unit_axis(i);
    const CylinderSurface<float, glm::vec3> s =
        cylinder_surface<float>(c.base(i), u, c.h[i], c.r[i], ray.o, ray.d, t);
    return from_float(s.p, s.n, cylinder_point_bound<float>(s, u, c.r[i]));
  }
  if (tracer.backend() == TracerBackend::kPacket && hit.prim.tag() == tag_of<MovingSphere>) {
    const MovingSphereTable& ms = scene.table<MovingSphere>();
    const uint32_t i = hit.prim.row();
    const glm::vec3 m = ms.motion(i), c = moving_center<float>(ms.start(i), m, ray.time);
    const SphereSurface<glm::vec3> s = sphere_surface<float>(c, ms.r[i], ray.o, ray.d, t);
    return from_float(s.p, s.n, moving_sphere_point_bound<float>(s, c, m, ray.time, ms.r[i]));
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
    if (hits[i].hit() && (tag == tag_of<Sphere> || tag == tag_of<Box> || tag == tag_of<Triangle> ||
                          tag == tag_of<Cylinder> || tag == tag_of<MovingSphere>))
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
