// Hostile scenes and meshes (docs/scene-language.md, "Limits"; docs/design.md, "Images in"): what
// is stored is finite after rounding to float and after a mesh's placement, for every kind; a PLY
// header longer than 64 KiB is read to its end, up to a documented limit; the textures and the
// environment share one image memory budget.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "raylane/scene/parser.h"
#include "raylane/scene/ply.h"
#include "scene/scene_test_util.h"
#include "support/hostile_files.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::errors;
using ::testing::HasSubstr;
using testing::kCameraLine;
using testing::parse;
using testing::temp_dir;

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string first_error(const ParsedScene& p) {
  auto e = errors(p);
  return e.empty() ? std::string("(no error)") : e[0];
}

// One triangle whose first vertex is (x, 0, 0), its coordinates of the given PLY type.
std::string ascii_ply(const std::string& type, const std::string& x) {
  return "ply\nformat ascii 1.0\nelement vertex 3\nproperty " + type + " x\nproperty " + type +
         " y\nproperty " + type +
         " z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" + x +
         " 0 0\n0 1 0\n0 0 1\n3 0 1 2\n";
}

ParsedScene load(const std::string& dir, const std::string& scene,
                 const ParseOptions& options = {}) {
  write_file(dir + "/s.scn", std::string(kCameraLine) + "brdf 0.5 0.5 0.5 0 0 0 1\n" + scene);
  return load_scene_file(dir + "/s.scn", options);
}

TEST(FiniteAfterRounding, PlyCoordinatesMustFitInAFloat) {
  std::string dir = temp_dir();
  write_file(dir + "/f.ply", ascii_ply("float", "1e39"));
  write_file(dir + "/d.ply", ascii_ply("double", "1e300"));
  write_file(dir + "/ok.ply", ascii_ply("double", "3e38"));
  for (std::string mesh : {"f.ply", "d.ply"}) {
    auto p = load(dir, "mesh " + mesh + " 0 0 0 1\n");
    EXPECT_THAT(first_error(p), HasSubstr("expected coordinates that fit in a float for vertex 0"))
        << mesh;
  }
  EXPECT_TRUE(load(dir, "mesh ok.ply 0 0 0 1\n").ok());
}

// t + s·R·p of a mesh line is checked for every vertex, through raylane's PLY reader and
// through Assimp (OBJ), with the error at the mesh line.
TEST(FiniteAfterPlacement, AMeshPlacedBeyondFloatIsAnErrorAtItsLine) {
  std::string dir = temp_dir();
  write_file(dir + "/m.ply", ascii_ply("float", "1e30"));
  write_file(dir + "/m.obj", "v 1e30 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n");
  for (std::string mesh : {"m.ply", "m.obj"}) {
    auto p = load(dir, "mesh " + mesh + " 0 0 0 1e10\n");
    EXPECT_THAT(first_error(p), HasSubstr("s.scn:3:6: mesh"));
    EXPECT_THAT(first_error(p), HasSubstr("vertex 0 (1.00000002e+30 0 0) is placed at "
                                          "(1.00000002e+40 0 0), beyond float"))
        << mesh;
    auto moved = load(dir, "mesh " + mesh + " 3e38 0 0 1e8\n");
    EXPECT_THAT(first_error(moved), HasSubstr("beyond float")) << mesh;
    EXPECT_TRUE(load(dir, "mesh " + mesh + " 0 0 0 1e8\n").ok()) << mesh;
  }
}

// Every kind's stored values and bounds are finite floats: a box corner, a sphere's and a
// cylinder's extent.
TEST(FiniteAfterRounding, PrimitivesReachingBeyondFloatAreErrors) {
  const std::pair<const char*, const char*> cases[] = {
      {"box 3e38 0 0 3e38 1 1\n", "box corner lies beyond float"},
      {"box 0 0 -3e38 1 1 -3e38\n", "box corner lies beyond float"},
      {"sphere 3e38 0 0 1e38\n", "sphere reaches beyond float"},
      {"cylinder 0 3e38 0 0 1e38 0 1\n", "cylinder reaches beyond float"},
  };
  for (const auto& [line, message] : cases) {
    auto p = parse(std::string(line) + kCameraLine);
    EXPECT_THAT(first_error(p), HasSubstr(message)) << line;
  }
  EXPECT_TRUE(
      parse(std::string("box 1e38 0 0 1e38 1 1\nsphere 1e38 0 0 1e38\n") + kCameraLine).ok());
}

// Long comment blocks: a header past 64 KiB reads; one past the documented limit is refused
// as too long, not as missing its end.
TEST(PlyHeader, IsReadToItsEndUpToTheLimit) {
  std::string dir = temp_dir();
  write_file(dir + "/long.ply", testing::ply_with_long_header(200 << 10));
  auto p = load(dir, "mesh long.ply 0 0 0 1\n");
  EXPECT_TRUE(p.ok()) << first_error(p);
  write_file(dir + "/huge.ply", testing::ply_with_long_header(kMaxPlyHeaderBytes + 100));
  auto huge = load(dir, "mesh huge.ply 0 0 0 1\n");
  EXPECT_THAT(first_error(huge), HasSubstr("PLY header is longer than 16 MiB"));
}

// The scene's textures and its environment take from one budget: each fits alone, not both.
TEST(ImageMemory, TexturesAndTheEnvironmentShareOneBudget) {
  std::string dir = temp_dir();
  write_file(dir + "/a.png", testing::png_zero_bomb(512, 512));
  write_file(dir + "/b.png", testing::png_zero_bomb(512, 512));
  ParseOptions options;
  // Reading a 512² PNG peaks at 2.75 MiB (decode_texels_bytes), keeping it takes 1 MiB of
  // 8-bit texels: 3.5 MiB hold one, not the second beside it.
  options.image_memory = 7 << 19;
  EXPECT_TRUE(load(dir, "texture a.png\n", options).ok());
  auto both = load(dir, "texture a.png\nbrdf 1 1 1 0 0 0 1\ntexture b.png\n", options);
  EXPECT_THAT(first_error(both), HasSubstr("s.scn:5:9: cannot use texture 'b.png'"));
  EXPECT_THAT(first_error(both), HasSubstr("(--image-memory MIB raises it)"));
  auto env = load(dir, "texture a.png\nenvironment b.png 1\n", options);
  EXPECT_THAT(first_error(env), HasSubstr("cannot use environment 'b.png'"));
  options.image_memory = 16 << 20;
  EXPECT_TRUE(load(dir, "texture a.png\nbrdf 1 1 1 0 0 0 1\ntexture b.png\n", options).ok());
}

// The language reads numbers as floats: a parameter that must be > 0 and rounds to 0 there
// (1e-46) says so, as a sphere radius does; one that underflows even in double (1e-400) is 0.
TEST(FiniteAfterRounding, PositiveParametersThatRoundToZeroAreErrors) {
  std::string dir = temp_dir();
  write_file(dir + "/sky.png", testing::png_zero_bomb(4, 2));
  const std::pair<std::string, std::string> cases[] = {
      {"environment sky.png 1e-46\n", "3:21: environment scale rounds to 0 in single precision"},
      {"environment sky.png 1e-400\n", "3:21: environment scale must be > 0"},
      {"lens 0.1 1e-46\n", "3:10: lens focus distance rounds to 0 in single precision"},
      {"camera 0 0 5 1e-46\n", "3:14: camera ry rounds to 0 in single precision"},
  };
  for (const auto& [line, message] : cases)
    EXPECT_THAT(first_error(load(dir, line)), HasSubstr(message)) << line;
}

TEST(Limits, AScreenSideBeyondThePixelLimitSaysSo) {
  auto p = parse(std::string(kCameraLine) + "screen 268435457 1\n");
  EXPECT_THAT(
      first_error(p),
      HasSubstr("2:8: screen side 268435457 is more than 2^28 (268435456), the pixel limit"));
}

// Assimp's validation fails a whole file on an empty mesh; the empty solid is dropped and the
// real one's triangle loads.
TEST(MeshRepair, AnEmptyStlSolidBesideARealOneIsDropped) {
  std::string dir = temp_dir();
  write_file(dir + "/two.stl",
             "solid empty\nendsolid empty\nsolid real\nfacet normal 0 0 1\nouter loop\n"
             "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid real\n");
  auto p = load(dir, "mesh two.stl 0 0 0 1\n");
  EXPECT_TRUE(p.ok()) << first_error(p);
  EXPECT_EQ(p.scene.primitive_count(), 1u);
}

}  // namespace
}  // namespace raylane
