// Textures named inside mesh files (docs/scene-language.md, "UV conventions", its last part): files
// next to the mesh (also when a Windows tool wrote the name), images embedded in the mesh file
// (glTF binary), JPEG among them, and what a missing one does.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "raylane/image/pfm.h"
#include "raylane/render/raycast.h"
#include "scene/scene_test_util.h"
#include "support/paths.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;
using testing::warnings;

const std::string kModels = RAYLANE_ASSIMP_MODELS;

// The duck of Debian's assimp-testmodels names duckCM.tga for its diffuse colour.
const std::string kDuck = kModels + "/Collada/duck.dae";

// A mesh in albedo mode, framed from its bounds: the colours of the pixels that hit it.
std::vector<glm::vec3> albedo_colours(const std::string& mesh_path,
                                      std::vector<std::string>* warns) {
  std::string head = "screen 64 64\nbrdf 1 1 1 0 0 0 0\nmesh \"" + mesh_path + "\" 0 0 0 1\n";
  auto probe = testing::parse(head + testing::kCameraLine);
  Bounds3f b = probe.meshes.at(0).bounds;
  glm::dvec3 c = 0.5 * (glm::dvec3(b.lo) + glm::dvec3(b.hi));
  double extent = length(glm::dvec3(b.hi) - glm::dvec3(b.lo));
  std::string camera = "camera " + std::to_string(c.x) + " " + std::to_string(c.y) + " " +
                       std::to_string(c.z + 3 * extent) + " 0.2\n";
  auto p = testing::parse(head + camera);
  EXPECT_TRUE(p.ok());
  if (warns) *warns = warnings(p);
  Bvh bvh = build_bvh_and_reorder(p.scene);
  Tracer tracer(p.scene, bvh, TracerBackend::kPacket);
  Image out = render_raycast(tracer, RaycastMode::kAlbedo);
  std::vector<glm::vec3> hit;
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x)
      if (out.at(x, y) != glm::vec3(0, 0, 0)) hit.push_back(out.at(x, y));
  return hit;
}

TEST(MeshTextures, TheDuckShowsItsOwnTexture) {
  if (!fs::exists(kDuck)) GTEST_SKIP() << "assimp-testmodels is not installed";
  std::vector<std::string> warns;
  auto colours = albedo_colours(kDuck, &warns);
  EXPECT_TRUE(warns.empty()) << ::testing::PrintToString(warns);
  ASSERT_GT(colours.size(), 200u);
  std::set<std::tuple<float, float, float>> distinct;
  glm::dvec3 mean(0, 0, 0);
  for (glm::vec3 c : colours) {
    distinct.insert({c.x, c.y, c.z});
    mean += glm::dvec3(c);
  }
  mean = mean / double(colours.size());
  EXPECT_GT(distinct.size(), 20u);  // a texture, not one colour
  EXPECT_GT(mean.x, 2 * mean.z);    // the duck is yellow: far more red than blue
  EXPECT_LE(mean.x, 1.0);           // Kd 1 times texels in [0, 1]
}

// A mesh's own texture makes a copy of the mesh line's material; a `microfacet` line after the
// mesh line still reaches that copy (docs/scene-language.md, "microfacet": the material's shapes
// before and after the line).
TEST(MeshTextures, TheTexturedCopyTakesAMicrofacetLineAfterTheMesh) {
  if (!fs::exists(kDuck)) GTEST_SKIP() << "assimp-testmodels is not installed";
  auto p = testing::parse(std::string(testing::kCameraLine) + "screen 8 8\nbrdf 1 1 1 0 0 0 0\n" +
                          "mesh \"" + kDuck + "\" 0 0 0 1\nmicrofacet ggx\n");
  ASSERT_TRUE(p.ok());
  int copies = 0;
  for (const Material& m : p.scene.materials) {
    EXPECT_EQ(m.microfacet, Microfacet::kGgx);
    copies += m.mesh_copy_of >= 0;
  }
  EXPECT_GT(copies, 0);
}

TEST(MeshTextures, AMissingTextureWarnsNamingTheMeshLineAndRendersUntextured) {
  if (!fs::exists(kDuck)) GTEST_SKIP() << "assimp-testmodels is not installed";
  std::string dir = testing::temp_dir();
  fs::copy_file(kDuck, dir + "/duck.dae");  // without duckCM.tga beside it
  std::vector<std::string> warns;
  auto colours = albedo_colours(dir + "/duck.dae", &warns);
  ASSERT_EQ(warns.size(), 1u);
  EXPECT_THAT(warns[0], ::testing::HasSubstr("t.scn:3:6: warning: mesh"));
  EXPECT_THAT(warns[0], ::testing::HasSubstr("duckCM.tga"));
  ASSERT_GT(colours.size(), 200u);
  for (glm::vec3 c : colours)
    ASSERT_EQ(c, glm::vec3(1, 1, 1));  // Kd alone
}

TEST(MeshTextures, GltfBaseColourTexture) {
  std::string box = kModels + "/glTF2/BoxTextured-glTF/BoxTextured.gltf";
  if (!fs::exists(box)) GTEST_SKIP() << "assimp-testmodels is not installed";
  auto p = testing::parse(std::string(testing::kCameraLine) + "screen 4 4\nbrdf 1 1 1 0 0 0 0\n" +
                          "mesh \"" + box + "\" 0 0 0 1\n");
  ASSERT_TRUE(p.ok());
  EXPECT_TRUE(warnings(p).empty()) << ::testing::PrintToString(warnings(p));
  ASSERT_EQ(p.scene.textures.size(), 1u);
  EXPECT_THAT(p.scene.textures[0].file, ::testing::HasSubstr("CesiumLogoFlat.png"));
  EXPECT_TRUE(p.scene.table<Triangle>().has_uv());
  for (uint32_t mat : p.scene.table<Triangle>().material)
    EXPECT_EQ(p.scene.materials[mat].texture, 0);
}

TEST(MeshTextures, AGlbEmbedsTheImageTheGltfNamesBeside) {
  // The same box, as .gltf with CesiumLogoFlat.png beside it and as .glb with the PNG inside.
  std::string gltf = kModels + "/glTF2/BoxTextured-glTF/BoxTextured.gltf";
  std::string glb = kModels + "/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb";
  if (!fs::exists(glb) || !fs::exists(gltf)) GTEST_SKIP() << "assimp-testmodels is not installed";
  auto p = testing::parse(std::string(testing::kCameraLine) +
                          "screen 4 4\nbrdf 1 1 1 0 0 0 0\nmesh \"" + glb + "\" 0 0 0 1\n");
  ASSERT_TRUE(p.ok());
  EXPECT_TRUE(warnings(p).empty()) << ::testing::PrintToString(warnings(p));
  ASSERT_EQ(p.scene.textures.size(), 1u);
  EXPECT_THAT(p.scene.textures[0].file, ::testing::HasSubstr("BoxTextured.glb [embedded *0]"));
  auto beside = testing::parse(std::string(testing::kCameraLine) +
                               "screen 4 4\nbrdf 1 1 1 0 0 0 0\nmesh \"" + gltf + "\" 0 0 0 1\n");
  ASSERT_EQ(beside.scene.textures.size(), 1u);
  EXPECT_EQ(to_float_image(p.scene.textures[0].texels).rgb,
            to_float_image(beside.scene.textures[0].texels).rgb);
  std::vector<std::string> warns;
  auto from_glb = albedo_colours(glb, &warns);
  ASSERT_GT(from_glb.size(), 200u);
  EXPECT_EQ(from_glb, albedo_colours(gltf, &warns));
}

TEST(MeshTextures, AJpegNamedTheWindowsWayIsFoundBesideTheMesh) {
  // jeep1.ms3d names its texture ".\\jeep1.jpg".
  std::string jeep = kModels + "/MS3D/jeep1.ms3d";
  if (!fs::exists(jeep)) GTEST_SKIP() << "assimp-testmodels is not installed";
  std::vector<std::string> warns;
  auto colours = albedo_colours(jeep, &warns);
  EXPECT_TRUE(warns.empty()) << ::testing::PrintToString(warns);
  std::set<std::tuple<float, float, float>> distinct;
  for (glm::vec3 c : colours)
    distinct.insert({c.x, c.y, c.z});
  EXPECT_GT(distinct.size(), 50u);  // the photo texture, not Kd alone
}

// An OBJ whose material names its texture `name`, and a 2×2 PFM texture at `dir`/t.pfm.
std::string obj_naming(const std::string& dir, const std::string& name) {
  std::ofstream(dir + "/m.mtl") << "newmtl m\nKd 1 1 1\nmap_Kd " << name << "\n";
  std::ofstream(dir + "/m.obj") << "mtllib m.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                   "vt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
  Image img(2, 2);
  img.set(0, 0, {0.25f, 0.5f, 0.75f});
  std::ofstream(dir + "/t.pfm", std::ios::binary) << encode_pfm(img);
  return dir + "/m.obj";
}

TEST(MeshTextures, AnAuthorsAbsolutePathFallsBackToTheFileNameBesideTheMesh) {
  // A Windows name (backslashes), an absolute name that is not where the file is, a bare name.
  for (int kind = 0; kind < 3; ++kind) {
    std::string dir = testing::temp_dir();
    std::string name = kind == 0   ? "..\\art\\maps\\t.pfm"
                       : kind == 1 ? dir + "/moved-away/t.pfm"
                                   : std::string("t.pfm");
    std::string obj = obj_naming(dir, name);
    auto p = testing::parse(std::string(testing::kCameraLine) +
                            "screen 4 4\nbrdf 1 1 1 0 0 0 0\nmesh \"" + obj + "\" 0 0 0 1\n");
    ASSERT_TRUE(p.ok()) << name;
    EXPECT_TRUE(warnings(p).empty()) << name << ::testing::PrintToString(warnings(p));
    ASSERT_EQ(p.scene.textures.size(), 1u) << name;
    EXPECT_EQ(fs::path(p.scene.textures[0].file).filename(), "t.pfm");
  }
  std::string dir = testing::temp_dir();
  std::string obj = obj_naming(dir, "art\\elsewhere.pfm");
  auto p = testing::parse(std::string(testing::kCameraLine) +
                          "screen 4 4\nbrdf 1 1 1 0 0 0 0\nmesh \"" + obj + "\" 0 0 0 1\n");
  ASSERT_EQ(warnings(p).size(), 1u);  // nothing of that name anywhere: a warning naming it
  EXPECT_THAT(warnings(p)[0], ::testing::HasSubstr("art/elsewhere.pfm"));
}

}  // namespace
}  // namespace raylane
