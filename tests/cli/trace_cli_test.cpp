// `raylane trace`: an external ray set against a triangle soup, answers in the soup's terms.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

#include "raylane/trace/ray_set_io.h"
#include "support/cli_run.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::read_file;
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

// The number after "key": in the JSON text; NaN if none.
double number_of(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": ([-0-9.eE+]+)[,}]")))
    return std::nan("");
  return std::stod(m[1]);
}

// One thread and SSE4.2 (4 lanes): 65 rays make 17 packets. In each of the first 16 every ray
// hits its own triangle, so the packet tests at least those 4: 64 tests or more over 65 rays.
TEST(CliTrace, StatsJsonSaysWhatTheTraversalDid) {
  std::string dir = temp_dir();
  write_inputs(dir, false);
  auto r = run_cli(
      "trace row.tris down.rays --repeat 2 --threads 1 --isa sse4.2 --stats-json t.json -q", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  std::string json = read_file(dir + "/t.json");
  ASSERT_FALSE(json.empty());
  EXPECT_EQ(json.substr(json.size() - 2), "}\n");
  for (const char* part :
       {"{\"mesh\": \"row.tris\", \"ray_set\": \"down.rays\", \"rays\": 65, \"query\": "
        "\"closest\", \"triangles\": 64, \"runs\": 2, ",
        "\"tracer\": \"packet\", \"isa\": \"sse4.2\", \"threads\": 1, ",
        "\"traversal\": {\"lanes\": 4, ", "\"outputs\": [\"down.hits\"]}"})
    EXPECT_NE(json.find(part), std::string::npos) << part << "\n" << json;
  EXPECT_GT(number_of(json, "mrays_per_second"), 0) << json;
  EXPECT_GT(number_of(json, "nodes_per_ray"), 0) << json;
  EXPECT_GE(number_of(json, "prims_per_ray") * 65, 64 - 1e-9) << json;
  const double lanes = number_of(json, "lanes_used");
  EXPECT_GT(lanes, 0) << json;
  EXPECT_LE(lanes, 1) << json;
  EXPECT_EQ(number_of(json, "wide_nodes"), 0) << json;  // 64 triangles: the binary tree only
  // The summary line is not printed with -q; the .hits path is.
  EXPECT_EQ(r.out.find("Mrays/s"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir + "/down.hits"));
}

// --tracer bvh and scalar (the double reference kernels) answer as the packet tracer does, for
// both kinds of query; their --stats-json has no traversal counters.
TEST(CliTrace, TheReferenceTracersGiveThePacketTracersAnswers) {
  for (bool occlusion : {false, true}) {
    std::string dir = temp_dir();
    write_inputs(dir, occlusion);
    ASSERT_EQ(run_cli("trace row.tris down.rays -o packet.hits -q", dir).status, 0);
    auto packet = read_hits(dir + "/packet.hits");
    ASSERT_TRUE(packet.ok()) << packet.error();
    for (std::string tracer : {"bvh", "scalar"}) {
      auto r = run_cli("trace row.tris down.rays --repeat 1 --threads 2 --tracer " + tracer +
                           " -o " + tracer + ".hits --stats-json " + tracer + ".json",
                       dir);
      ASSERT_EQ(r.status, 0) << r.out;
      EXPECT_NE(r.out.find("the " + tracer + " reference"), std::string::npos) << r.out;
      auto hits = read_hits(dir + "/" + tracer + ".hits");
      ASSERT_TRUE(hits.ok()) << hits.error();
      ASSERT_EQ(hits->size(), packet->size());
      for (std::size_t i = 0; i < hits->size(); ++i) {
        EXPECT_EQ((*hits)[i].prim, (*packet)[i].prim) << tracer << " ray " << i;
        EXPECT_EQ((*hits)[i].t, (*packet)[i].t) << tracer << " ray " << i;
      }
      std::string json = read_file(dir + "/" + tracer + ".json");
      EXPECT_NE(json.find("\"tracer\": \"" + tracer + "\""), std::string::npos) << json;
      EXPECT_NE(json.find("\"traversal\": null"), std::string::npos) << json;
    }
  }
  std::string dir = temp_dir();
  write_inputs(dir, false);
  auto bad = run_cli("trace row.tris down.rays --tracer fast", dir);
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("unknown --tracer 'fast' (packet, bvh, scalar)"), std::string::npos)
      << bad.out;
}

// The --stats-json file is an output like the .hits file: never an input or the other output,
// checked for writability before tracing; with any of these wrong nothing is written.
TEST(CliTrace, TheStatsJsonIsCheckedAsAnOutputBeforeTracing) {
  std::string dir = temp_dir();
  write_inputs(dir, false);
  const std::string rays = read_file(dir + "/down.rays");
  auto onto_input = run_cli("trace row.tris down.rays --stats-json ./down.rays", dir);
  EXPECT_EQ(onto_input.status, 2);
  EXPECT_NE(onto_input.out.find("the --stats-json file"), std::string::npos) << onto_input.out;
  EXPECT_EQ(read_file(dir + "/down.rays"), rays);
  auto onto_mesh = run_cli("trace row.tris down.rays --stats-json row.tris", dir);
  EXPECT_EQ(onto_mesh.status, 2) << onto_mesh.out;
  auto onto_hits = run_cli("trace row.tris down.rays -o a.hits --stats-json a.hits", dir);
  EXPECT_EQ(onto_hits.status, 2) << onto_hits.out;
  auto unwritable = run_cli("trace row.tris down.rays --stats-json no/such/dir.json", dir);
  EXPECT_EQ(unwritable.status, 2);
  EXPECT_NE(unwritable.out.find("cannot write no/such/dir.json"), std::string::npos)
      << unwritable.out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/down.hits"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/a.hits"));
}

// A file name that is not UTF-8 stays JSON: its stray byte becomes U+FFFD.
TEST(CliTrace, StatsJsonNamesAnyFileInUtf8) {
  std::string dir = temp_dir();
  write_inputs(dir, false);
  std::filesystem::rename(dir + "/down.rays", dir + "/d\xff.rays");
  // The shell (sh, through popen) writes the byte with printf's octal escape.
  auto r =
      run_cli("trace row.tris \"$(printf 'd\\377.rays')\" -o d.hits --stats-json t.json -q", dir);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(read_file(dir + "/t.json").find("\"ray_set\": \"d\\ufffd.rays\""), std::string::npos)
      << read_file(dir + "/t.json");
}

}  // namespace
}  // namespace raylane
