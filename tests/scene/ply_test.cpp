// raylane's own PLY reader (scene/ply.h): the same mesh in ASCII and in both binary byte
// orders reads alike, every scalar type and the attribute names exporters use are read, faces
// are cut right, other elements are skipped, and damaged files say where they are damaged.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "raylane/scene/mesh_import.h"
#include "raylane/scene/ply.h"

namespace raylane {
namespace {

// Binary PLY bodies, value by value, in either byte order.
class BinaryWriter {
 public:
  explicit BinaryWriter(bool big_endian) : big_(big_endian) {}
  template <class T>
  BinaryWriter& put(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof v);
    if (big_ != (std::endian::native == std::endian::big))
      for (std::size_t k = 0; k < sizeof v / 2; ++k)
        std::swap(b[k], b[sizeof v - 1 - k]);
    bytes.append(reinterpret_cast<const char*>(b), sizeof v);
    return *this;
  }
  std::string bytes;

 private:
  bool big_;
};

// A unit square in z = 0 with normals and UVs, as one quad, and an edge element to skip.
const char* const kSquareHeader =
    "element vertex 4\nproperty double x\nproperty float y\nproperty int16 z\n"
    "property float nx\nproperty float ny\nproperty float nz\nproperty float s\n"
    "property float t\nelement edge 1\nproperty list uint8 int32 ends\nproperty uchar red\n"
    "element face 1\nproperty uchar flags\nproperty list ushort uint vertex_indices\n"
    "end_header\n";

std::string square_ascii() {
  return std::string("ply\nformat ascii 1.0\n") + kSquareHeader +
         "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 0 0 1 1 1\n0 1 0 0 0 1 0 1\n"
         "2 0 1 255\n7 4 0 1 2 3\n";
}

std::string square_binary(bool big) {
  BinaryWriter w(big);
  const double xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const auto& v : xy) {
    w.put(v[0]).put(float(v[1])).put(int16_t(0));
    w.put(0.0f).put(0.0f).put(1.0f).put(float(v[0])).put(float(v[1]));
  }
  w.put(uint8_t(2)).put(int32_t(0)).put(int32_t(1)).put(uint8_t(255));
  w.put(uint8_t(7)).put(uint16_t(4));
  for (uint32_t i = 0; i < 4; ++i)
    w.put(i);
  return std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
         " 1.0\n" + kSquareHeader + w.bytes;
}

TEST(PlyReader, AsciiAndBothByteOrdersReadAlike) {
  std::vector<PlyMesh> meshes;
  for (const std::string& bytes : {square_ascii(), square_binary(false), square_binary(true)}) {
    auto m = read_ply(bytes, "square.ply");
    ASSERT_TRUE(m) << m.error();
    meshes.push_back(*m);
  }
  for (const PlyMesh& m : meshes) {
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.positions[2], glm::vec3(1, 1, 0));
    ASSERT_EQ(m.normals.size(), 4u);
    EXPECT_EQ(m.normals[3], glm::vec3(0, 0, 1));
    ASSERT_EQ(m.uvs.size(), 4u);  // s and t are texture coordinates
    EXPECT_EQ(m.uvs[1].u, 1.0);
    EXPECT_EQ(m.uvs[1].v, 0.0);
    ASSERT_EQ(m.triangles.size(), 2u);
    EXPECT_EQ(m.triangles, meshes[0].triangles);
  }
}

// The area of a mesh's triangles; a quad cut along its outside diagonal covers more.
double area(const PlyMesh& m) {
  double a = 0;
  for (const auto& t : m.triangles) {
    glm::dvec3 p0(m.positions[t[0]]), p1(m.positions[t[1]]), p2(m.positions[t[2]]);
    a += 0.5 * length(cross(p1 - p0, p2 - p0));
  }
  return a;
}

std::string polygon_ply(const std::vector<std::array<float, 2>>& corners) {
  std::string s = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(corners.size()) +
                  "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
                  "property list uchar int vertex_indices\nend_header\n";
  for (const auto& c : corners)
    s += std::to_string(c[0]) + " " + std::to_string(c[1]) + " 0\n";
  s += std::to_string(corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i)
    s += " " + std::to_string(i);
  return s + "\n";
}

TEST(PlyReader, QuadsAreCutInsideThemAndPolygonsAsFans) {
  // A dart: its reflex corner is corner 1, so the diagonal 0-2 lies outside it. Area 1.
  auto dart = read_ply(polygon_ply({{0, 0}, {1, 1}, {2, 0}, {1, 2}}), "dart.ply");
  ASSERT_TRUE(dart) << dart.error();
  EXPECT_NEAR(area(*dart), 1.0, 1e-6);
  auto convex = read_ply(polygon_ply({{0, 0}, {2, 0}, {2, 1}, {0, 1}}), "quad.ply");
  ASSERT_TRUE(convex) << convex.error();
  EXPECT_NEAR(area(*convex), 2.0, 1e-6);
  auto pentagon = read_ply(polygon_ply({{0, 0}, {2, 0}, {3, 1}, {1, 2}, {-1, 1}}), "pentagon.ply");
  ASSERT_TRUE(pentagon) << pentagon.error();
  EXPECT_EQ(pentagon->triangles.size(), 3u);
  EXPECT_NEAR(area(*pentagon), 5.0, 1e-6);  // shoelace: (0+2+5+3+1)/2
}

TEST(PlyReader, FacesOfFewerThanThreeCornersAreCounted) {
  std::string s =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 3\nproperty list uchar int vertex_index\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n0\n2 0 1\n3 0 1 2\n";
  auto m = read_ply(s, "few.ply");
  ASSERT_TRUE(m) << m.error();
  EXPECT_EQ(m->triangles.size(), 1u);
  EXPECT_EQ(m->faces_skipped, 2u);
}

TEST(PlyReader, TextureFileCommentIsKept) {
  std::string s =
      "ply\nformat ascii 1.0\ncomment TextureFile  my texture.png \nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\nproperty float u\n"
      "property float v\nelement face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n";
  auto m = read_ply(s, "tex.ply");
  ASSERT_TRUE(m) << m.error();
  ASSERT_EQ(m->texture_files.size(), 1u);
  EXPECT_EQ(m->texture_files[0], "my texture.png");
  EXPECT_EQ(m->uvs.size(), 3u);
}

struct Damaged {
  std::string bytes, error;
};

std::string triangle_header(const char* format) {
  return std::string("ply\nformat ") + format +
         " 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
}

TEST(PlyReader, DamagedBodiesSayWhere) {
  // The header is 9 lines: the body's first vertex is on line 10.
  const std::string ascii = triangle_header("ascii");
  const std::string binary_header = triangle_header("binary_little_endian");
  BinaryWriter short_body(false);
  short_body.put(0.0f).put(0.0f).put(0.0f).put(1.0f);
  const Damaged cases[] = {
      // found by fuzz_mesh: Assimp leaked its half-built mesh on a letter inside a number
      {ascii + "0 0 0\n1 0 0\n0 1.2x5 0\n3 0 1 2\n",
       "d.ply:12:3: expected a number that fits the declared type, found '1.2x5'"},
      {ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
       "d.ply:13:7: expected a vertex index below 3 in face 0, found 3"},
      {ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n",
       "d.ply:13:5: expected an integer that fits the declared type, found '1.5'"},
      {ascii + "0 0 0\n1 0 0\n0 1 0\n256 0 1 2\n",
       "d.ply:13:1: expected an integer that fits the declared type, found '256'"},
      // found by fuzz_mesh: an integer written far beyond int64's range (converting it was
      // undefined behaviour)
      {ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 2.2e118 2\n",
       "d.ply:13:5: expected an integer that fits the declared type, found '2.2e118'"},
      {ascii + "0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n",
       "d.ply:11:7: expected finite coordinates for vertex 1, found (1 inf 0)"},
      {ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "d.ply:14:1: expected a number, found the end"},
      {binary_header + short_body.bytes, "d.ply: byte " +
                                             std::to_string(binary_header.size() + 16) +
                                             ": expected 4 more bytes, found the end of the file"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1 "
       "2\n",
       "expected the PLY 'vertex' element to have properties x, y and z"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nelement face 1\nproperty list uchar int corners\nend_header\n"
       "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "expected the PLY 'face' element to have a list property 'vertex_indices'"},
  };
  for (const Damaged& c : cases) {
    auto m = read_ply(c.bytes, "d.ply");
    ASSERT_FALSE(m) << c.error;
    EXPECT_NE(m.error().find(c.error), std::string::npos) << m.error();
  }
}

// A list whose count announces more items than the file has left is refused before anything
// is read for it.
TEST(PlyReader, ListLongerThanTheFileIsRefused) {
  BinaryWriter w(false);
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f})
    w.put(v);
  w.put(uint8_t(200)).put(int32_t(0));
  auto m = read_ply(triangle_header("binary_little_endian") + w.bytes, "long.ply");
  ASSERT_FALSE(m);
  EXPECT_NE(m.error().find("expected a list length the file can hold, found 200"),
            std::string::npos)
      << m.error();
}

// A unit cube, every face cut along its diagonal through corner 0 or 6: each other corner
// meets two triangles on one of its faces and one on each of the other two. As a triangle
// soup, every triangle has its own three vertices.
std::string cube_ply(bool soup) {
  const float corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                              {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int tri[12][3] = {{0, 2, 1}, {0, 3, 2}, {0, 1, 5}, {0, 5, 4}, {0, 4, 7}, {0, 7, 3},
                          {6, 5, 1}, {6, 1, 2}, {6, 2, 3}, {6, 3, 7}, {6, 7, 4}, {6, 4, 5}};
  std::string vertices, faces;
  auto vertex = [&](int c) {
    vertices += std::to_string(corner[c][0]) + " " + std::to_string(corner[c][1]) + " " +
                std::to_string(corner[c][2]) + "\n";
  };
  if (!soup)
    for (int c = 0; c < 8; ++c)
      vertex(c);
  for (int t = 0; t < 12; ++t) {
    faces += "3";
    for (int k = 0; k < 3; ++k) {
      if (soup) vertex(tri[t][k]);
      faces += " " + std::to_string(soup ? 3 * t + k : tri[t][k]);
    }
    faces += "\n";
  }
  return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(soup ? 36 : 8) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face 12\n"
         "property list uchar int vertex_indices\nend_header\n" +
         vertices + faces;
}

// Normals made for a file without them weight each corner by its angle (Thürmer and
// Wüthrich 1998): a cube's corner gets the diagonal direction however its faces were cut,
// which neither equal weights nor area weights give when a corner meets two triangles on one
// face and one on another. Vertices at one position share the normal, so a soup gets the same.
TEST(PlyImport, MadeNormalsDoNotDependOnHowFacesWereCut) {
  for (bool soup : {false, true}) {
    SCOPED_TRACE(soup ? "soup" : "indexed");
    TriangleTable table;
    auto r =
        import_mesh_memory(cube_ply(soup), "cube.ply", {{0, 0, 0}, 1.0, glm::dmat3(1.0)}, 0, table);
    ASSERT_TRUE(r) << r.error();
    ASSERT_EQ(table.size(), 12u);
    for (uint32_t i = 0; i < table.size(); ++i) {
      std::array<glm::vec3, 3> p = {table.p0(i), table.p1(i), table.p2(i)};
      std::array<glm::vec3, 3> n = {table.n0(i), table.n1(i), table.n2(i)};
      for (int k = 0; k < 3; ++k) {
        glm::dvec3 outward = normalize(glm::dvec3(p[k]) - glm::dvec3(0.5, 0.5, 0.5));
        EXPECT_NEAR(length(glm::dvec3(n[k]) - outward), 0.0, 1e-6)
            << "row " << i << " corner " << k;
      }
    }
  }
}

}  // namespace
}  // namespace raylane
