// `raylane trace`: an external ray set against a triangle soup, answers in the soup's terms.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "raylane/trace/ray_set_io.h"
#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::run_cli;
using testing::temp_dir;

// 64 small horizontal triangles in a row along x, triangle i at height z = i, so the BVH
// reorders them and each ray's answer names exactly one.
void write_inputs(const std::string& dir, bool occlusion) {
  TriangleTable soup;
  glm::vec3 n(0, 0, 1);
  for (int i = 0; i < 64; ++i) {
    float x = float(i) * 3, z = float(i);
    soup.append({glm::vec3(x - 1, -1, z), glm::vec3(x + 1, -1, z), glm::vec3(x, 1, z)}, {n, n, n},
                0);
  }
  ASSERT_TRUE(write_triangle_soup(dir + "/row.tris", soup).ok());
  RaySetFile set;
  set.flags = occlusion ? kRaySetOcclusionFlag : 0;
  set.rays.resize(65);
  for (int i = 0; i < 64; ++i)  // straight down onto triangle i from z = 100
    set.rays.set(std::size_t(i), Rayf{{float(i) * 3, 0, 100}, {0, 0, -1}, 0, 1e30f});
  set.rays.set(64, Rayf{{-50, 0, 100}, {0, 0, -1}, 0, 1e30f});  // misses everything
  ASSERT_TRUE(write_ray_set(dir + "/down.rays", set).ok());
}

// With one thread and two: the command splits the stream over its threads itself.
TEST(CliTrace, WritesAnswersInTheSoupsOrder) {
  for (std::string threads : {"1", "2"}) {
    std::string dir = temp_dir();
    write_inputs(dir, false);
    auto r = run_cli("trace row.tris down.rays --repeat 3 --threads " + threads, dir);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("Mrays/s"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(threads == "1" ? " 1 thread;" : " 2 threads;"), std::string::npos)
        << r.out;
    auto hits = read_hits(dir + "/down.hits");
    ASSERT_TRUE(hits.ok()) << hits.error();
    ASSERT_EQ(hits->size(), 65u);
    for (uint32_t i = 0; i < 64; ++i) {
      EXPECT_EQ((*hits)[i].prim, i) << threads;
      EXPECT_EQ((*hits)[i].t, 100.0f - float(i)) << threads;
    }
    EXPECT_EQ((*hits)[64].prim, kNoHit);
    EXPECT_TRUE(std::isinf((*hits)[64].t));
  }
}

TEST(CliTrace, OcclusionSetsAnswerOccludedOrNot) {
  std::string dir = temp_dir();
  write_inputs(dir, true);
  auto r = run_cli("trace row.tris down.rays -o shadow.hits --isa sse4.2", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  uint32_t flags = 0;
  auto hits = read_hits(dir + "/shadow.hits", &flags);
  ASSERT_TRUE(hits.ok()) << hits.error();
  EXPECT_EQ(flags, kRaySetOcclusionFlag);
  EXPECT_EQ((*hits)[0].prim, 0u);
  EXPECT_EQ((*hits)[64].prim, kNoHit);
}

TEST(CliTrace, BadInputIsAnErrorAndWritesNothing) {
  std::string dir = temp_dir();
  write_inputs(dir, false);
  std::filesystem::resize_file(dir + "/down.rays", 100);  // truncated
  auto r = run_cli("trace row.tris down.rays", dir);
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("down.rays: the header announces 65 records"), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/down.hits"));
  EXPECT_EQ(run_cli("trace row.tris", dir).status, 2);
  EXPECT_EQ(run_cli("trace row.tris down.rays --repeat 0", dir).status, 2);
  auto bad = run_cli("trace row.tris down.rays --isa diagonal", dir);
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("unknown --isa 'diagonal'"), std::string::npos) << bad.out;
}

}  // namespace
}  // namespace raylane
