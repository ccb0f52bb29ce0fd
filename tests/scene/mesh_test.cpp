// Meshes through Assimp: the course's letters, placement, normals, and bad files.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "raylane/scene/mesh_import.h"
#include "scene/scene_test_util.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::errors;
using testing::source_path;
using testing::temp_dir;

void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

MeshPlacement identity() {
  return {{0, 0, 0}, 1.0, glm::dmat3(1.0)};
}

TEST(MeshImport, LettersHaveTheirTriangles) {
  TriangleTable x, y;
  auto sx = import_mesh_file(source_path("scenes/letterX.ply"), identity(), 7, x);
  auto sy = import_mesh_file(source_path("scenes/letterY.ply"), identity(), 7, y);
  ASSERT_TRUE(sx) << sx.error();
  ASSERT_TRUE(sy) << sy.error();
  EXPECT_EQ(sx->triangles, 4u);
  EXPECT_EQ(sy->triangles, 6u);
  EXPECT_EQ(x.size(), 4u);
  EXPECT_EQ(x.material[0], 7u);
  for (uint32_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(x.p0(i).z, 0.0f);
    // Flat letters: every normal is ±z, unit length.
    EXPECT_NEAR(std::abs(x.n0(i).z), 1.0f, 1e-6f);
    EXPECT_NEAR(length(glm::dvec3(x.n2(i))), 1.0, 1e-6);
  }
}

TEST(MeshImport, PlacementIsTranslateScaleRotate) {
  TriangleTable plain, placed;
  glm::dmat3 r = rotation_axis_angle({1, 0, 0}, 90);
  MeshPlacement pl{{1, 2, 3}, 0.5, r};
  ASSERT_TRUE(import_mesh_file(source_path("scenes/letterY.ply"), identity(), 0, plain));
  ASSERT_TRUE(import_mesh_file(source_path("scenes/letterY.ply"), pl, 0, placed));
  ASSERT_EQ(plain.size(), placed.size());
  for (uint32_t i = 0; i < plain.size(); ++i) {
    glm::dvec3 want = glm::dvec3(1, 2, 3) + 0.5 * (r * glm::dvec3(plain.p1(i)));
    EXPECT_NEAR(placed.p1(i).x, want.x, 1e-6);
    EXPECT_NEAR(placed.p1(i).y, want.y, 1e-6);
    EXPECT_NEAR(placed.p1(i).z, want.z, 1e-6);
    // Normals turn with R (z → −y under Rx(90)) and stay unit.
    glm::dvec3 n = r * glm::dvec3(plain.n1(i));
    EXPECT_NEAR(placed.n1(i).y, n.y, 1e-6);
    EXPECT_NEAR(length(glm::dvec3(placed.n1(i))), 1.0, 1e-6);
  }
}

TEST(MeshImport, TestSceneLettersLieOnTheTable) {
  auto p = load_scene_file(source_path("scenes/testscene.scn"));
  ASSERT_TRUE(p.ok());
  const auto& t = p.scene.table<Triangle>();
  for (uint32_t i = 0; i < t.size(); ++i) {
    EXPECT_FLOAT_EQ(t.p0(i).z, 0.42f);
    EXPECT_LT(std::abs(t.p0(i).x), 1.2f);  // within the 2.4-wide table top
    EXPECT_LT(std::abs(t.p0(i).y), 1.2f);
  }
}

TEST(MeshImport, MissingFileNamesFileAndLine) {
  std::string dir = temp_dir();
  write_file(dir + "/s.scn", "camera 0 0 5 1\n\nmesh nothere.ply 0 0 0 1\n");
  auto p = load_scene_file(dir + "/s.scn");
  ASSERT_EQ(errors(p).size(), 1u);
  EXPECT_EQ(errors(p)[0], dir + "/s.scn:3:6: mesh file 'nothere.ply' not found (looked in '" + dir +
                              "' and the working directory)");
}

TEST(MeshImport, EmptyAndGarbageFilesAreErrors) {
  std::string dir = temp_dir();
  write_file(dir + "/empty.ply", "");
  write_file(dir + "/garbage.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\n");
  write_file(dir + "/noface.ply",
             "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
             "y\nproperty float z\nend_header\n0 0 0\n");
  write_file(dir + "/s.scn",
             "camera 0 0 5 1\nmesh empty.ply 0 0 0 1\nmesh garbage.ply 0 0 0 1\n"
             "mesh noface.ply 0 0 0 1\nmesh s.scn 0 0 0 1\n");
  auto p = load_scene_file(dir + "/s.scn");
  ASSERT_EQ(errors(p).size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NE(errors(p)[i].find(":" + std::to_string(i + 2) + ":6: "), std::string::npos)
        << errors(p)[i];
  }
  EXPECT_EQ(p.scene.table<Triangle>().size(), 0u);
  EXPECT_TRUE(p.scene.materials.empty());
}

TEST(MeshImport, ScaleMustBePositive) {
  auto p = testing::parse("camera 0 0 5 1\nmesh a.ply 0 0 0 0\n");
  EXPECT_THAT(errors(p), ::testing::ElementsAre("t.scn:2:18: mesh scale must be > 0"));
}

TEST(MeshImport, ZeroAreaTrianglesAreDroppedWithAWarning) {
  std::string dir = temp_dir();
  write_file(dir + "/m.ply",
             "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float "
             "y\nproperty float z\nelement face 2\nproperty list uchar int "
             "vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 2 2\n3 3 3\n3 0 1 2\n3 0 3 "
             "4\n");
  write_file(dir + "/s.scn",
             "camera 0 0 5 1\nscreen 4 3\nbrdf 1 1 1 0 0 0 1\nmesh m.ply 0 0 0 1\n");
  auto p = load_scene_file(dir + "/s.scn");
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  EXPECT_EQ(p.scene.table<Triangle>().size(), 1u);
  ASSERT_EQ(testing::warnings(p).size(), 1u);
  EXPECT_NE(testing::warnings(p)[0].find("skipped 1 zero-area triangles"), std::string::npos);
}

// Assimp refuses a whole OBJ file for one index outside its lists; raylane drops those faces,
// as docs/scene-language.md says, and names their lines. Kept: positive and negative indices
// in range, "v//vn" and "v/vt" forms. Dropped: a vertex past the end, a negative index reaching
// before the first vertex, a texture coordinate and a normal past the end, index 0.
TEST(MeshImport, ObjFacesNamingMissingElementsAreDroppedWithTheirLines) {
  std::string dir = temp_dir();
  write_file(dir + "/m.obj",
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvn 0 0 1\n"
             "f 1 2 3\n"           // 7: kept
             "f -3 -1 -2\n"        // 8: kept (vertices 2, 4, 3)
             "f 1//1 2//1 4//1\n"  // 9: kept
             "f 1/1 2/1 3/1\n"     // 10: kept
             "f 2 4 9\n"           // 11: vertex 9 of 4
             "f -5 1 2\n"          // 12: before the first vertex
             "f 1/2 2/1 3/1\n"     // 13: texture coordinate 2 of 1
             "f 1//1 2//7 3//1\n"  // 14: normal 7 of 1
             "f 0 1 2\n");         // 15: index 0
  write_file(dir + "/s.scn",
             "camera 0 0 5 1\nscreen 4 3\nbrdf 1 1 1 0 0 0 1\nmesh m.obj 0 0 0 1\n");
  auto p = load_scene_file(dir + "/s.scn");
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  EXPECT_EQ(p.scene.table<Triangle>().size(), 4u);
  ASSERT_EQ(testing::warnings(p).size(), 1u);
  EXPECT_NE(testing::warnings(p)[0].find("s.scn:4:6: warning: skipped 5 faces of"),
            std::string::npos)
      << testing::warnings(p)[0];
  EXPECT_NE(testing::warnings(p)[0].find("(lines 11, 12, 13, 14, 15)"), std::string::npos)
      << testing::warnings(p)[0];
}

TEST(MeshImport, EmittingMeshTrianglesAreLights) {
  auto p = testing::parse("camera 0 0 5 1\nlight 1 1 1\nmesh " + source_path("scenes/letterX.ply") +
                          " 0 0 0 1\n");
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  EXPECT_EQ(p.scene.lights.size(), 4u);
  EXPECT_EQ(p.scene.lights[3], PrimRef(tag_of<Triangle>, 3));
}

}  // namespace
}  // namespace raylane
