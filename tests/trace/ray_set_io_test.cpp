// The ray-set exchange files (docs/ray-sets.md): exact layout, round trips, hostile headers.
#include <gtest/gtest.h>
#include <array>
#include <limits>

#include <cmath>
#include <cstring>
#include <fstream>

#include "raylane/trace/ray_set_io.h"
#include "support/paths.h"

namespace raylane {
namespace {

std::string write_bytes(const std::string& name, const std::string& bytes) {
  std::string path = testing::temp_dir() + "/" + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

template <class T>
void append(std::string& s, T v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// A file built byte by byte from the spec, independent of our writer.
TEST(RaySetIo, ReadsTheSpecLayout) {
  std::string b("RAYSET1\0", 8);
  for (uint32_t w : {1u, 1u, 4u, 4u, 0u, 0u})
    append(b, w);  // count, flags, width, height
  for (float v : {1.f, 2.f, 3.f, 0.f, 0.f, -1.f, 0.f, 1e30f})
    append(b, v);
  auto set = read_ray_set(write_bytes("one.rays", b));
  ASSERT_TRUE(set.ok()) << set.error();
  EXPECT_TRUE(set->occlusion());
  EXPECT_EQ(set->width, 4u);
  ASSERT_EQ(set->rays.size(), 1u);
  Rayf r = set->rays.get(0);
  EXPECT_EQ(r.o, glm::vec3(1, 2, 3));
  EXPECT_EQ(r.d, glm::vec3(0, 0, -1));
  EXPECT_EQ(r.tmax, 1e30f);
}

// The format's rays have finite origins and unit directions (docs/ray-sets.md): anything else
// is refused with the record's index, not traced into NaNs.
TEST(RaySetIo, RefusesRaysThatAreNotRays) {
  struct Case {
    std::array<float, 8> v;
    const char* says;
  };
  const float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
  for (const Case& c : {Case{{nan, 0, 0, 0, 0, 1, 0, 5}, "a finite origin"},
                        Case{{0, inf, 0, 0, 0, 1, 0, 5}, "a finite origin"},
                        Case{{0, 0, 0, 0, 0, 0, 0, 5}, "a unit direction"},
                        Case{{0, 0, 0, 2, 0, 0, 0, 5}, "a unit direction"},
                        Case{{0, 0, 0, 0, nan, 1, 0, 5}, "a unit direction"},
                        Case{{0, 0, 0, 0, 0, 1, nan, 5}, "t bounds that are numbers"}}) {
    std::string b("RAYSET1\0", 8);
    for (uint32_t w : {2u, 0u, 0u, 0u, 0u, 0u})
      append(b, w);
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f})  // ray 0 is fine
      append(b, v);
    for (float v : c.v)
      append(b, v);
    auto set = read_ray_set(write_bytes("bad.rays", b));
    ASSERT_FALSE(set.ok()) << c.says;
    EXPECT_NE(set.error().find(": ray 1: expected " + std::string(c.says)), std::string::npos)
        << set.error();
  }
  // Within the tolerance: a direction normalised in float is accepted.
  std::string b("RAYSET1\0", 8);
  for (uint32_t w : {1u, 0u, 0u, 0u, 0u, 0u})
    append(b, w);
  for (float v : {0.f, 0.f, 0.f, 0.6f, 0.8f, 1e-7f, 0.f, 1.f})
    append(b, v);
  EXPECT_TRUE(read_ray_set(write_bytes("ok.rays", b)).ok());
}

TEST(RaySetIo, RoundTripsRaysTrianglesAndHits) {
  std::string dir = testing::temp_dir();
  RaySetFile set;
  set.rays.resize(3);
  for (uint32_t i = 0; i < 3; ++i)
    set.rays.set(i, Rayf{{float(i), 0, 0}, {0, 1, 0}, 0, 5});
  ASSERT_TRUE(write_ray_set(dir + "/a.rays", set).ok());
  auto back = read_ray_set(dir + "/a.rays");
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->rays.ox, set.rays.ox);
  EXPECT_EQ(back->rays.tmax, set.rays.tmax);

  TriangleTable soup;
  glm::vec3 n(0, 0, 1);
  soup.append({glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}, {n, n, n}, 0);
  soup.append({glm::vec3(0, 0, 1), glm::vec3(0, 1, 1), glm::vec3(1, 0, 1)}, {n, n, n}, 0);
  ASSERT_TRUE(write_triangle_soup(dir + "/a.tris", soup).ok());
  TriangleTable read;
  auto count = read_triangle_soup(dir + "/a.tris", 7, read);
  ASSERT_TRUE(count.ok()) << count.error();
  EXPECT_EQ(*count, 2u);
  EXPECT_EQ(read.p2(1), glm::vec3(1, 0, 1));
  EXPECT_EQ(read.n0(1), glm::vec3(0, 0, -1));  // the face normal by the winding
  EXPECT_EQ(read.material[0], 7u);

  std::vector<HitRecord> hits = {{1.5f, 0}, {INFINITY, kNoHit}};
  ASSERT_TRUE(write_hits(dir + "/a.hits", hits, 0).ok());
  uint32_t flags = 9;
  auto hb = read_hits(dir + "/a.hits", &flags);
  ASSERT_TRUE(hb.ok()) << hb.error();
  EXPECT_EQ(flags, 0u);
  ASSERT_EQ(hb->size(), 2u);
  EXPECT_EQ((*hb)[0].t, 1.5f);
  EXPECT_EQ((*hb)[1].prim, kNoHit);
}

// A header may announce anything: nothing is allocated for it before the file's size
// confirms it, and each problem is named.
TEST(RaySetIo, HostileHeadersAreErrors) {
  std::string b("RAYSET1\0", 8);
  append(b, 0x7fffffffu);  // announces 2^31 − 1 rays
  b.resize(32, '\0');
  auto huge = read_ray_set(write_bytes("huge.rays", b));
  ASSERT_FALSE(huge.ok());
  EXPECT_NE(huge.error().find("limit"), std::string::npos) << huge.error();

  std::string c("RAYSET1\0", 8);
  append(c, 2u);
  c.resize(32 + 40, '\0');  // two records need 64 bytes
  auto short_file = read_ray_set(write_bytes("short.rays", c));
  ASSERT_FALSE(short_file.ok());
  EXPECT_NE(short_file.error().find("announces 2 records (96 bytes), the file has 72"),
            std::string::npos)
      << short_file.error();

  auto magic = read_ray_set(write_bytes("wrong.rays", std::string(40, 'x')));
  ASSERT_FALSE(magic.ok());
  EXPECT_NE(magic.error().find("expected the magic 'RAYSET1'"), std::string::npos) << magic.error();

  auto tiny = read_hits(write_bytes("tiny.hits", "HITS"));
  ASSERT_FALSE(tiny.ok());
  EXPECT_NE(tiny.error().find("16-byte header"), std::string::npos) << tiny.error();

  EXPECT_FALSE(read_ray_set(testing::temp_dir() + "/missing.rays").ok());
}

TEST(RaySetIo, NonFiniteVerticesAreAnErrorAndAppendNothing) {
  std::string b("TRISOUP1", 8);
  append(b, 2u);
  append(b, 0u);
  for (int i = 0; i < 9; ++i)
    append(b, float(i));
  for (int i = 0; i < 9; ++i)
    append(b, i == 4 ? NAN : float(i));
  TriangleTable t;
  auto r = read_triangle_soup(write_bytes("nan.tris", b), 0, t);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("triangle 1"), std::string::npos) << r.error();
  EXPECT_EQ(t.size(), 0u);
}

}  // namespace
}  // namespace raylane
