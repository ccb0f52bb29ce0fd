// Inputs found by fuzz_mesh (tests/fuzz), kept as regressions: each once crashed, aborted or
// leaked inside Assimp; now each is an error or a clean import, never a crash. Since PLY files
// are read by raylane's own reader (scene/ply.h), the PLY ones check that reader.
#include <gtest/gtest.h>

#include <string>

#include "raylane/scene/mesh_guard.h"
#include "raylane/scene/mesh_import.h"

namespace raylane {
namespace {

template <std::size_t N>
std::string bytes_of(const char (&literal)[N]) {
  return std::string(literal, N - 1);  // keeps embedded NULs
}

MeshPlacement identity() {
  return {{0, 0, 0}, 1.0, glm::dmat3(1.0)};
}

// Assimp 5.2.5 segfaulted on this binary PLY: `end_header` inside an element line, a non-text
// byte in a property line, and a list property without types. The guard rejects the header.
TEST(MeshFuzzRegression, MalformedPlyHeaderIsAnError) {
  std::string ply = bytes_of(
      "ply\nformat binary_little_endian 0.0\nelement vertex 3\nproperty float x\nproperty "
      "float y\nproperty fl\377oat z\nelemend_headerent face 1\nproperty "
      "list\000\000\003\000\000\000\000\001\000\000\000\002\000\000\000");
  TriangleTable table;
  auto r = import_mesh_memory(ply, "crash1.ply", identity(), 0, table);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("PLY header line 2"), std::string::npos) << r.error();
  EXPECT_EQ(table.size(), 0u);
}

// One stray byte shifts the binary body so the face's list count reads 0; Assimp's
// triangulation asserted on the empty face and aborted the process.
TEST(MeshFuzzRegression, EmptyFaceInBinaryPlyDoesNotAbort) {
  std::string ply = bytes_of(
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty "
      "float y\nproperty float z\nelement face 1\nproperty list uchar int "
      "vertex_indices\nend_header\n\000\000\000\007\000\000\000\000\000\000\000\000\000\000"
      "\000\200?\000\000\000\000\000\000\000\000\000\000\000\000\000\000\200?\000\000\000\000"
      "\003\000\000\000\000\001\000\000\000\002\000\000\000");
  TriangleTable table;
  auto r = import_mesh_memory(ply, "crash2.ply", identity(), 0, table);
  ASSERT_FALSE(r);  // the only face is empty: no triangles
  EXPECT_EQ(table.size(), 0u);
}

// The same in ASCII, as a user could write it: an empty face beside a good one is skipped.
TEST(MeshFuzzRegression, EmptyFaceInAsciiPlyIsSkipped) {
  std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n0\n3 0 1 2\n";
  TriangleTable table;
  auto r = import_mesh_memory(ply, "empty_face.ply", identity(), 0, table);
  ASSERT_TRUE(r) << r.error();
  EXPECT_EQ(r->triangles, 1u);
}

// Vertex lines cut short: an error (Assimp reported one too, and leaked its half-built mesh).
TEST(MeshFuzzRegression, TruncatedAsciiPlyIsAnError) {
  std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n";
  TriangleTable table;
  EXPECT_FALSE(import_mesh_memory(ply, "short.ply", identity(), 0, table));
  EXPECT_EQ(table.size(), 0u);
}

// `Ply` in any case is PLY to Assimp, which looped for minutes on this header (no vertex
// element, a list property without types); the guard used to look for lowercase `ply` only.
TEST(MeshFuzzRegression, PlyInOtherCaseIsCheckedToo) {
  std::string ply =
      "Ply\nformat ascii 1.0\ncomment letterX of the CS50rty float x\nproperty float y\n"
      "property float z\nelement face 2\nproperty list43985 0\n4 3 2 1 0\n4 7 6 5 4\n";
  for (const char* name : {"timeout.ply", "timeout.obj"}) {
    TriangleTable table;
    auto r = import_mesh_memory(ply, name, identity(), 0, table);
    ASSERT_FALSE(r) << name;
    EXPECT_NE(r.error().find("PLY header line 1"), std::string::npos) << r.error();
  }
  // A .ply name without a PLY header is not left to Assimp's guesses either.
  std::string not_ply = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_FALSE(check_mesh_plausible(not_ply, not_ply.size(), "x.PLY"));
  EXPECT_TRUE(check_mesh_plausible(not_ply, not_ply.size(), "x.obj"));
}

TEST(MeshGuard, AcceptsTheFullPlyGrammar) {
  std::string header =
      "ply\r\nformat binary_big_endian 1.0\r\ncomment made by hand\nobj_info x\n"
      "element vertex 1\nproperty float32 x\nproperty double y\nproperty uint8 z\n"
      "element face 0\nproperty list uint8 int32 vertex_indices\nend_header\r\n";
  EXPECT_TRUE(check_mesh_plausible(header + std::string(16, '\0'), header.size() + 16, "a.ply"));
}

// Blender 2.47 wrote a line of free text into the header without `comment` (Wuson.ply of
// Debian's assimp-testmodels); Assimp skips it, so the guard must too.
TEST(MeshGuard, SkipsFreeTextLinesAsAssimpDoes) {
  std::string header =
      "ply\nformat ascii 1.0\nCreated by Blender3D 247 - www.blender.org, source file: \n"
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  std::string ply = header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  TriangleTable table;
  auto r = import_mesh_memory(ply, "free.ply", identity(), 0, table);
  ASSERT_TRUE(r) << r.error();
  EXPECT_EQ(table.size(), 1u);
}

TEST(MeshGuard, RejectsWhatIsNotPlyGrammar) {
  for (const char* bad :
       {"ply\nformat ascii 2.0\nend_header\n",
        "ply\nformat ascii 1.0\nproperty float x\n"
        "end_header\n",
        "ply\nformat ascii 1.0\nelement v 1\nproperty list float int i\nend_header\n",
        "ply\nformat ascii 1.0\nelement v -1\nend_header\n",
        "ply\nformat ascii 1.0\nelement v 1\nproperty float x\nend_header x\n"}) {
    std::string s = std::string(bad) + "0 0 0\n";
    EXPECT_FALSE(check_mesh_plausible(s, s.size(), "b.ply")) << bad;
  }
}

// A 297-byte ASCII PLY whose vertex element was named otherwise made Assimp 5.2.5 request
// 22.9 GB (out of memory under the fuzzer's 2 GiB limit); so did the same file with its
// faces declared before the vertices. The guard requires a `vertex` element first.
TEST(MeshFuzzRegression, PlyWithoutAVertexElementIsAnError) {
  const std::string body = "end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  const std::string vertices =
      "element %s 4\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\n";
  auto ply = [&](const std::string& first, const std::string& second) {
    return "ply\nformat ascii 1.0\n" + first + second + body;
  };
  auto named = [&](const std::string& n) {
    std::string v = vertices;
    return v.replace(v.find("%s"), 2, n);
  };
  struct Case {
    std::string bytes, error;
  } cases[] = {
      {ply(named("vertexNSt6locale5"), faces), "expected a PLY 'vertex' element, found none"},
      {ply(named("points"), faces), "expected a PLY 'vertex' element, found none"},
      {ply(faces, named("vertex")), "expected the PLY 'vertex' element before 'face'"},
  };
  for (const Case& c : cases) {
    TriangleTable table;
    auto r = import_mesh_memory(c.bytes, "oom.ply", identity(), 0, table);
    ASSERT_FALSE(r) << c.bytes;
    EXPECT_NE(r.error().find(c.error), std::string::npos) << r.error();
    EXPECT_EQ(table.size(), 0u);
  }
  TriangleTable table;  // the same file with its vertices named `vertex` imports: 2 triangles
  auto good = import_mesh_memory(ply(named("vertex"), faces), "good.ply", identity(), 0, table);
  ASSERT_TRUE(good) << good.error();
  EXPECT_EQ(table.size(), 2u);
}

}  // namespace
}  // namespace raylane
