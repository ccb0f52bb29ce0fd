// The triangle's reference kernel (docs/hard-cases.md §1).
#include <gtest/gtest.h>

#include <random>

#include "prims/prim_test_util.h"

namespace raylane {
namespace {

using namespace testing;

TEST(TriangleRef, AnalyticHitBarycentricsAndNormals) {
  TriangleTable t;
  glm::vec3 n0(0, 0, 1), n1(1, 0, 0), n2(0, 1, 0);
  t.append({glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}, {n0, n1, n2}, 0);
  Rayd r = ray({0.25, 0.25, 2}, {0, 0, -1});
  EXPECT_EQ(intersect_ref(t, 0, r), 2.0);
  Surface s = surface_ref(t, 0, r, 2.0);
  EXPECT_EQ(s.ng, glm::dvec3(0, 0, 1));
  EXPECT_NEAR(s.p.x, 0.25, 1e-16);
  // b = (0.5, 0.25, 0.25): interpolated normal (0.25, 0.25, 0.5), normalised.
  EXPECT_NEAR(s.ns.z, 0.5 / std::sqrt(0.375), 1e-15);
  // From below (back face): still a hit (no culling, T7).
  EXPECT_EQ(intersect_ref(t, 0, ray({0.25, 0.25, -2}, {0, 0, 1})), 2.0);
  EXPECT_EQ(intersect_ref(t, 0, ray({0.75, 0.75, 2}, {0, 0, -1})), kInf);
}

// T3: the quad's diagonal, hit exactly: at least one of the two triangles reports it.
TEST(TriangleRef, SharedDiagonalIsWatertight) {
  TriangleTable t;
  add_triangle(t, {-5, -5, 0}, {5, -5, 0}, {5, 5, 0});
  add_triangle(t, {-5, -5, 0}, {5, 5, 0}, {-5, 5, 0});
  glm::dvec3 d(0.30458447, 0.30458447, -0.9024725);
  Rayd r = ray({0, 0, 10}, glm::dvec3(glm::vec3(d)));
  EXPECT_TRUE(intersect_ref(t, 0, r) < kInf || intersect_ref(t, 1, r) < kInf);
}

// T3: a fan of 8 triangles around a vertex; rays through the shared vertex from many
// directions hit at least one.
TEST(TriangleRef, FanVertexIsWatertight) {
  TriangleTable t;
  glm::dvec3 centre(0.1, 0.2, 0.3);
  for (int k = 0; k < 8; ++k) {
    double a0 = k * 2 * M_PI / 8, a1 = (k + 1) * 2 * M_PI / 8;
    add_triangle(t, centre, centre + glm::dvec3(std::cos(a0), std::sin(a0), 0.1 * std::sin(3 * a0)),
                 centre + glm::dvec3(std::cos(a1), std::sin(a1), 0.1 * std::sin(3 * a1)));
  }
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  glm::dvec3 v(glm::vec3(t.p0(0)));
  for (int i = 0; i < 20000; ++i) {
    glm::dvec3 o = v + glm::dvec3(g(rng), g(rng), std::abs(g(rng)) + 0.5) * 3.0;
    Rayd r = ray(o, v - o);
    bool hit = false;
    for (uint32_t k = 0; k < t.size(); ++k)
      hit |= intersect_ref(t, k, r) < kInf;
    ASSERT_TRUE(hit) << i;
  }
}

// T4: zero-area triangles are never hit, and give no NaN.
TEST(TriangleRef, ZeroAreaTrianglesAreNeverHit) {
  TriangleTable t;
  add_triangle(t, {0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  add_triangle(t, {0, 0, 0}, {0, 0, 0}, {1, 0, 0});
  add_triangle(t, {1, 1, 1}, {1, 1, 1}, {1, 1, 1});
  std::mt19937 rng(8);
  std::normal_distribution<double> g;
  for (int i = 0; i < 30000; ++i) {
    Rayd r = ray({g(rng), g(rng), g(rng)}, {g(rng), g(rng), g(rng)});
    if (i % 3 == 0) r = ray({-1, -1, -1}, {1, 1, 1});  // along the degenerate line
    for (uint32_t k = 0; k < 3; ++k)
      ASSERT_EQ(intersect_ref(t, k, r), kInf);
  }
}

// T5: tiny triangles: no absolute epsilon anywhere, so s = 2e-4 … 1e-6 are hit at t = 1 —
// unless rounding the vertices to float already collapsed the triangle (s below the float
// spacing at the offset), which is then rejected as zero-area.
TEST(TriangleRef, TinyTrianglesAreHit) {
  for (double off : {0.0, 1e3})
    for (double s : {1e-3, 2e-4, 1e-5, 1e-6}) {
      TriangleTable t;
      add_triangle(t, {off, off, 0}, {off + s, off, 0}, {off, off + s, 0});
      glm::dvec3 p0(t.p0(0)), p1(t.p1(0)), p2(t.p2(0));
      glm::dvec3 c = (p0 + p1 + p2) / 3.0;
      double hit = intersect_ref(t, 0, ray({c.x, c.y, -1}, {0, 0, 1}));
      if (length_squared(cross(p1 - p0, p2 - p0)) == 0) {
        EXPECT_EQ(hit, kInf) << off << " " << s;
        EXPECT_GT(off, 0);  // only the offset one may collapse
      } else {
        EXPECT_NEAR(hit, 1.0, 4 * 0x1p-52) << off << " " << s;
      }
    }
}

// T6: huge triangles: rays landing near the shared diagonal of a ±1e5 quad hit one of them.
TEST(TriangleRef, HugeQuadHasNoGapsNearTheDiagonal) {
  for (double big : {1e5, 1e6}) {
    TriangleTable t;
    add_triangle(t, {-big, 0, -big}, {big, 0, big}, {big, 0, -big});
    add_triangle(t, {-big, 0, -big}, {-big, 0, big}, {big, 0, big});
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-10, 10), e(-1e-3, 1e-3);
    for (int i = 0; i < 20000; ++i) {
      double x = u(rng), z = x + e(rng);
      glm::dvec3 o(0, 1.7, 0);
      Rayd r = ray(o, normalize(glm::dvec3(x, 0, z) - o));
      double t0 = intersect_ref(t, 0, r), t1 = intersect_ref(t, 1, r);
      ASSERT_TRUE(t0 < kInf || t1 < kInf) << big << " " << i;
      double th = std::min(t0, t1);
      EXPECT_NEAR(r.at(th).y, 0.0, 1e-9);
    }
  }
}

// T8: pbrt-v4's TEST(Triangle, BadCases): the ray stops short of the triangle's plane.
TEST(TriangleRef, PbrtBadCaseIsNotHit) {
  TriangleTable t;
  add_triangle(t, {-1113.45459, -79.049614, -56.2431908}, {-1113.45459, -87.0922699, -56.2431908},
               {-1113.45459, -79.2090149, -56.2431908});
  Rayd r = ray({-1081.47925, 99.9999542, 87.7701111}, {-32.1072998, -183.355865, -144.607635});
  r.tmax = 0.9999;
  EXPECT_EQ(intersect_ref(t, 0, r), kInf);
}

// triangle_surface (pbrt-v4 §6.8.5's barycentric reconstruction) at double and at float: rays
// aimed at a known point P = Σ bᵢ·pᵢ of random triangles (every b ≥ 0.05, distinct, so that a
// vertex's weight given to another shows) from 1 to 10 edges away, at least 0.3 of the way
// along the normal. The point must be P and the shading normal the vertex normals blended by b,
// within 1e-12 of an edge at double and 1e-4 at float: the float ray passes P within a few
// roundoffs of |o| + t (about 1e-6 here), which a cosine of 0.3 magnifies less than tenfold, where
// a wrong weight moves the point by 0.05 of an edge or more.
template <class N, class V3>
void expect_barycentric_surfaces(double tolerance) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g;
  std::normal_distribution<float> gf;
  auto gauss3 = [&] {  // in order: a constructor's arguments are evaluated in any order
    const double x = g(rng), y = g(rng);
    return glm::dvec3(x, y, g(rng));
  };
  // Vertices and normals drawn as floats, so that the test's double copy of one and the float
  // one the surface is given are the same number by construction. Drawn as doubles and
  // rounded, the copies differed by 1e-9 in this -O3 build (the point aimed at lay off the
  // float triangle's plane, the expected normal off the blended one): the rounding to float
  // was not applied to both alike, as GCC 12's SLP vectoriser dropped a double → float →
  // double round trip in PacketBackend::closest's loop (src/trace/packet_backend.cpp).
  auto vertex = [&](const glm::vec3& centre) {
    const float x = gf(rng), y = gf(rng);
    return centre + glm::vec3(x, y, gf(rng));
  };
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 centre = vertex(glm::vec3(0.0f)) * 3.0f;
    const std::array<glm::vec3, 3> v{vertex(centre), vertex(centre), vertex(centre)};
    const glm::vec3 zero(0.0f);
    const std::array<glm::vec3, 3> vn{normalize(vertex(zero)), normalize(vertex(zero)),
                                      normalize(vertex(zero))};
    const glm::dvec3 p0(v[0]), p1(v[1]), p2(v[2]);
    const glm::dvec3 normal = cross(p1 - p0, p2 - p0);
    const double edge = std::max({length(p1 - p0), length(p2 - p0), length(p2 - p1)});
    if (length(normal) < 0.2 * edge * edge) continue;  // a sliver: its barycentrics are fragile
    double b1 = u(rng), b2 = u(rng);
    if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
    const double b0 = 1 - b1 - b2;
    if (std::min({b0, b1, b2}) < 0.05) continue;
    const glm::dvec3 at = b0 * p0 + b1 * p1 + b2 * p2;
    const glm::dvec3 away = normalize(gauss3());
    if (std::abs(dot(away, normalize(normal))) < 0.3) continue;
    const glm::dvec3 o = at + away * edge * (1 + 9 * u(rng));
    const V3 ro(o), rd(normalize(at - o));
    const auto t = static_cast<N>(length(at - glm::dvec3(ro)));
    const std::array<V3, 3> pv{V3(v[0]), V3(v[1]), V3(v[2])}, nv{V3(vn[0]), V3(vn[1]), V3(vn[2])};
    const TriangleSurface<V3> s = triangle_surface<N>(pv, nv, ro, rd, t);
    ASSERT_LE(length(glm::dvec3(s.p) - at), tolerance * edge) << i;
    const glm::dvec3 ns =
        normalize(b0 * glm::dvec3(vn[0]) + b1 * glm::dvec3(vn[1]) + b2 * glm::dvec3(vn[2]));
    ASSERT_LE(length(glm::dvec3(s.ns) - ns), tolerance) << i;
    ASSERT_LE(length(glm::dvec3(s.ng) - normalize(normal)), tolerance) << i;
    ++checked;
  }
  EXPECT_GT(checked, 2000);
}

TEST(TriangleSurface, BarycentricPointAndNormalsAtDouble) {
  expect_barycentric_surfaces<double, glm::dvec3>(1e-12);
}

TEST(TriangleSurface, BarycentricPointAndNormalsAtFloat) {
  expect_barycentric_surfaces<float, glm::vec3>(1e-4);
}

// A degenerate triangle's barycentrics are not numbers: the point is q = o + t·d, bounded as a
// hit point is (float_hit_point_bound's 34 roundoffs of |o| + |t·d|, and γ7 of the largest
// vertex coordinate), and its cross product has no direction, so the normal faces the ray
// (zero-area triangles are never hit, T4, but no input may give a NaN).
TEST(TriangleSurface, WithoutBarycentricsThePointIsTheTracedOne) {
  const std::array<glm::vec3, 3> v{glm::vec3(0, 0, 0), glm::vec3(1, 1, 1), glm::vec3(2, 2, 2)};
  const std::array<glm::vec3, 3> vn{glm::vec3(0, 0, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, 0)};
  const glm::vec3 o(0.5f, 0.5f, 3), d(0, 0, -1);
  const TriangleSurface<glm::vec3> s = triangle_surface<float>(v, vn, o, d, 2.5f);
  EXPECT_EQ(s.p, glm::vec3(0.5f, 0.5f, 0.5f));
  EXPECT_EQ(s.ng, glm::vec3(0, 0, 1));
  EXPECT_EQ(s.ns, glm::vec3(0, 0, 1));  // the vertex normals have no direction either
  const glm::vec3 e = triangle_point_bound<float>(s, v, o, d, 2.5f);
  EXPECT_GE(e.x, float(34 * 0x1p-24 * 0.5 + 2 * gamma_float(7)));
  EXPECT_GE(e.z, float(34 * 0x1p-24 * 5.5 + 2 * gamma_float(7)));
}

// Tiny and huge triangles (docs/hard-cases.md T5, T6) at float: edges of 1e-20 at the origin,
// whose cross product (1e-40) is below float's normal range, and of 1e15, whose shares
// overflow float: the normals are unit vectors, the point finite and on the plane z = 0, for a
// ray straight down onto the triangle's centroid.
TEST(TriangleSurface, TinyAndHugeTrianglesHaveUnitNormals) {
  for (float s : {1e-20f, 1e-12f, 1e3f, 1e15f}) {
    SCOPED_TRACE(s);
    const std::array<glm::vec3, 3> v{glm::vec3(0, 0, 0), glm::vec3(s, 0, 0), glm::vec3(0, s, 0)};
    const std::array<glm::vec3, 3> vn{glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1)};
    const glm::vec3 o(s / 3, s / 3, s), d(0, 0, -1);
    const TriangleSurface<glm::vec3> x = triangle_surface<float>(v, vn, o, d, s);
    EXPECT_EQ(x.ng, glm::vec3(0, 0, 1));
    EXPECT_EQ(x.ns, glm::vec3(0, 0, 1));
    EXPECT_TRUE(std::isfinite(x.p.x) && std::isfinite(x.p.y)) << x.p.x << " " << x.p.y;
    EXPECT_EQ(x.p.z, 0.0f);
    const glm::vec3 e = triangle_point_bound<float>(x, v, o, d, s);
    EXPECT_TRUE(std::isfinite(e.x) && std::isfinite(e.y) && std::isfinite(e.z));
  }
}

}  // namespace
}  // namespace raylane
