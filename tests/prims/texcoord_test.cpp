// Texture coordinates per kind (prims/<kind>.h, texcoord_ref) against the formulas of
// docs/scene-language.md, "UV conventions", at points where the answer is known exactly.
#include <gtest/gtest.h>

#include "raylane/prims/box.h"
#include "raylane/prims/cylinder.h"
#include "raylane/prims/sphere.h"
#include "raylane/prims/triangle.h"

namespace raylane {
namespace {

constexpr double kTol = 1e-12;

template <class Table, std::size_t N>
Table one_row(const std::array<double, N>& params) {
  Table t;
  EXPECT_FALSE(t.append(std::span<const double, N>(params), 0));
  return t;
}

void expect_uv(const TexCoord& t, double u, double v, const char* where) {
  EXPECT_NEAR(t.u, u, kTol) << where;
  EXPECT_NEAR(t.v, v, kTol) << where;
}

TEST(TexCoord, SphereLongitudeFromPlusXAndLatitudeUpFromTheSouthPole) {
  auto t = one_row<SphereTable>(std::array<double, 4>{1, 2, 3, 2});
  glm::dvec3 c(1, 2, 3);
  auto at = [&](glm::dvec3 d) { return texcoord_ref(t, 0, Surface{c + 2.0 * d, d, d}); };
  expect_uv(at({1, 0, 0}), 0.0, 0.5, "phi = 0 on the equator");
  expect_uv(at({0, 1, 0}), 0.25, 0.5, "phi = pi/2");
  expect_uv(at({-1, 0, 0}), 0.5, 0.5, "phi = pi");
  expect_uv(at({0, -1, 0}), 0.75, 0.5, "phi = 3pi/2 (atan2 < 0 wraps)");
  EXPECT_NEAR(at({0, 0, 1}).v, 1.0, kTol) << "the top pole";
  EXPECT_NEAR(at({0, 0, -1}).v, 0.0, kTol) << "the bottom pole";
  glm::dvec3 mid = normalize(glm::dvec3(1, 0, 1));  // 45 degrees up: theta = pi/4
  expect_uv(at(mid), 0.0, 0.75, "theta = pi/4");
}

TEST(TexCoord, BoxFacesRunAlongTheOtherAxesInXyzOrder) {
  auto t = one_row<BoxTable>(std::array<double, 6>{0, 0, 0, 2, 4, 8});
  auto at = [&](glm::dvec3 p, glm::dvec3 n) { return texcoord_ref(t, 0, Surface{p, n, n}); };
  expect_uv(at({2, 1, 6}, {1, 0, 0}), 0.25, 0.75, "face normal to +x: u along y, v along z");
  expect_uv(at({0, 3, 2}, {-1, 0, 0}), 0.75, 0.25, "face normal to -x");
  expect_uv(at({0.5, 0, 2}, {0, -1, 0}), 0.25, 0.25, "face normal to y: u along x, v along z");
  expect_uv(at({1.5, 1, 8}, {0, 0, 1}), 0.75, 0.25, "face normal to z: u along x, v along y");
}

TEST(TexCoord, CylinderSideAroundTheAxisFrameAndCapsCentred) {
  auto t = one_row<CylinderTable>(std::array<double, 7>{0, 0, 0, 0, 0, 4, 1});
  auto at = [&](glm::dvec3 p, glm::dvec3 n) { return texcoord_ref(t, 0, Surface{p, n, n}); };
  // For the axis +Z the frame is s = +X, t = +Y (docs/scene-language.md, "UV conventions").
  expect_uv(at({1, 0, 1}, {1, 0, 0}), 0.0, 0.25, "side at s");
  expect_uv(at({0, 1, 2}, {0, 1, 0}), 0.25, 0.5, "side at t");
  expect_uv(at({0, -1, 3}, {0, -1, 0}), 0.75, 0.75, "side at -t");
  expect_uv(at({0.5, 0, 4}, {0, 0, 1}), 0.75, 0.5, "top cap");
  expect_uv(at({0, -0.5, 0}, {0, 0, -1}), 0.5, 0.25, "bottom cap");
  // A tilted axis: the frame is the axis's own, so the cap's centre is (0.5, 0.5) and a side
  // point's v is its height along the axis. The table's axis is its rounded unit axis times its
  // rounded height (cylinder.h), within a few ulps of (3, 0, 4): the points are placed on it.
  auto tilted = one_row<CylinderTable>(std::array<double, 7>{1, 1, 1, 3, 0, 4, 2});
  const double height = length(tilted.axis(0));
  glm::dvec3 a = normalize(tilted.axis(0));
  Frame f(a);
  glm::dvec3 side = glm::dvec3(1, 1, 1) + (0.5 * height) * a + 2.0 * f.t;
  expect_uv(texcoord_ref(tilted, 0, Surface{side, f.t, f.t}), 0.25, 0.5, "tilted side");
  glm::dvec3 top = glm::dvec3(1, 1, 1) + height * a;
  expect_uv(texcoord_ref(tilted, 0, Surface{top, a, a}), 0.5, 0.5, "tilted cap centre");
}

TEST(TexCoord, TriangleInterpolatesItsVertexUvs) {
  TriangleTable t;
  t.add_uv_columns();
  std::array<TexCoord, 3> uv{TexCoord{0.2, 0.1}, TexCoord{0.9, 0.3}, TexCoord{0.4, 0.8}};
  glm::vec3 n(0, 0, 1);
  t.append({glm::vec3(0, 0, 0), glm::vec3(2, 0, 0), glm::vec3(0, 2, 0)}, {n, n, n}, 0, &uv);
  // p = 0.5·p0 + 0.25·p1 + 0.25·p2.
  glm::dvec3 p(0.5, 0.5, 0);
  TexCoord got = texcoord_ref(t, 0, Surface{p, {0, 0, 1}, {0, 0, 1}});
  EXPECT_NEAR(got.u, 0.5 * 0.2 + 0.25 * 0.9 + 0.25 * 0.4, 1e-7);
  EXPECT_NEAR(got.v, 0.5 * 0.1 + 0.25 * 0.3 + 0.25 * 0.8, 1e-7);
  TriangleTable bare;  // no UV columns: (0, 0)
  bare.append({glm::vec3(0, 0, 0), glm::vec3(2, 0, 0), glm::vec3(0, 2, 0)}, {n, n, n}, 0, &uv);
  EXPECT_FALSE(bare.has_uv());
  expect_uv(texcoord_ref(bare, 0, Surface{p, {0, 0, 1}, {0, 0, 1}}), 0, 0, "no UVs");
}

TEST(TexCoord, OptionalColumnsFollowAPermutation) {
  TriangleTable t;
  glm::vec3 n(0, 0, 1);
  t.append({glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}, {n, n, n}, 0);
  t.add_uv_columns();  // the earlier row gets (0, 0)
  std::array<TexCoord, 3> uv{TexCoord{1, 2}, TexCoord{3, 4}, TexCoord{5, 6}};
  t.append({glm::vec3(0, 0, 1), glm::vec3(1, 0, 1), glm::vec3(0, 1, 1)}, {n, n, n}, 0, &uv);
  ASSERT_EQ(t.t0u.size(), 2u);
  EXPECT_EQ(t.t0u[0], 0.0f);
  std::vector<uint32_t> order{1, 0};
  table_permute(t, order);
  EXPECT_EQ(t.p0z[0], 1.0f);
  EXPECT_EQ(t.t0u[0], 1.0f);
  EXPECT_EQ(t.t2v[0], 6.0f);
  EXPECT_EQ(t.t0u[1], 0.0f);
  EXPECT_EQ(table_bytes(t), 2 * (19 * 4 + 6 * 4));
}

}  // namespace
}  // namespace raylane
