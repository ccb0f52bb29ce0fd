// Textures (docs/scene-language.md, "Beyond project 4: textures, environment, lens"): the lookup
// (bilinear, v up, repeat), the `texture` command, textures named inside mesh files, and what
// the ray-casting views show.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "raylane/image/pfm.h"
#include "raylane/render/raycast.h"
#include "raylane/scene/parser.h"
#include "scene/scene_test_util.h"
#include "support/paths.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;
using testing::errors;
using testing::warnings;

// A 4×4 image whose texel (x, row) has a colour no other texel has; row 0 is the file's top.
Image distinct_4x4() {
  Image img(4, 4);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x)
      img.set(x, y, {float(x + 1), float(y + 1) * 10, float(x * 4 + y) * 0.5f});
  return img;
}

std::string write_pfm(const std::string& dir, const std::string& name, const Image& img) {
  std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << encode_pfm(img);
  return path;
}

glm::dvec3 texel(const Image& img, uint32_t x, uint32_t row_from_top) {
  return glm::dvec3(img.at(x, row_from_top));
}

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tol, const std::string& where) {
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(a[k], b[k], tol) << where << " channel " << k;
}

TEST(TextureLookup, TexelCentresBilinearBetweenVUpAndRepeat) {
  Image img = distinct_4x4();
  // Texel centres: u = (x + 0.5)/4; v = 0 is the bottom row (row 3 of the file).
  for (uint32_t x = 0; x < 4; ++x)
    for (uint32_t r = 0; r < 4; ++r) {
      double u = (x + 0.5) / 4, v = (3 - r + 0.5) / 4;
      expect_near(texture_lookup(img, u, v), texel(img, x, r), 0, "centre");
    }
  // Halfway between two centres in u, a quarter of the way in v.
  glm::dvec3 mid_u = 0.5 * (texel(img, 1, 3) + texel(img, 2, 3));
  expect_near(texture_lookup(img, 0.5, 0.125), mid_u, 1e-12, "between columns 1 and 2");
  glm::dvec3 quarter_v = 0.75 * texel(img, 0, 3) + 0.25 * texel(img, 0, 2);
  expect_near(texture_lookup(img, 0.125, 0.1875), quarter_v, 1e-12, "a quarter up");
  // Repeat: u and v shift by whole numbers; at u = 0 the last and first columns blend.
  expect_near(texture_lookup(img, 2.375, -0.625), texture_lookup(img, 0.375, 0.375), 1e-12,
              "repeat");
  glm::dvec3 seam = 0.5 * (texel(img, 3, 3) + texel(img, 0, 3));
  expect_near(texture_lookup(img, 0.0, 0.125), seam, 1e-12, "the u seam");
}

// A box whose face z = 0 is [0, 1]² seen head-on by a camera that frames exactly that square
// on an n×n screen, textured with `texture` in albedo mode.
Image albedo_of_face(const std::string& texture_line, uint32_t n) {
  std::string scene = "screen " + std::to_string(n) + " " + std::to_string(n) +
                      "\ncamera 0.5 0.5 10 0.05\nbrdf 1 1 1 0 0 0 0\n" + texture_line +
                      "\nbox 0 0 -1 1 1 1\n";
  auto p = parse_scene(scene, testing::temp_dir() + "/face.scn");
  EXPECT_TRUE(p.ok()) << ::testing::PrintToString(errors(p));
  Bvh bvh = build_bvh_and_reorder(p.scene);
  Tracer tracer(p.scene, bvh, TracerBackend::kPacket);
  return render_raycast(tracer, RaycastMode::kAlbedo);
}

TEST(TextureAlbedo, BoxFaceHeadOnShowsEachTexelWhereTheSpecPutsIt) {
  std::string dir = testing::temp_dir();
  Image img = distinct_4x4();
  std::string path = write_pfm(dir, "t.pfm", img);
  // 4×4 pixels over 4×4 texels: each pixel centre is a texel centre. The face normal to z has
  // u along x and v along y; the image's top row is the picture's top row.
  Image out = albedo_of_face("texture \"" + path + "\"", 4);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x)
      expect_near(glm::dvec3(out.at(x, y)), texel(img, x, y), 1e-4, "pixel");
  // 8×8 pixels: centres a quarter of a texel from the texel centres, so bilinear mixes 3:1.
  Image fine = albedo_of_face("texture \"" + path + "\"", 8);
  glm::dvec3 want = 0.75 * (0.75 * texel(img, 1, 1) + 0.25 * texel(img, 2, 1)) +
                    0.25 * (0.75 * texel(img, 1, 0) + 0.25 * texel(img, 2, 0));
  // Pixel (3, 2) of 8: u = 3.5/8 → 0.75 of column 1; its row from the top is 2 → v from the
  // top 2.5/8, 0.75 of row 1 and 0.25 of row 0.
  expect_near(glm::dvec3(fine.at(3, 2)), want, 1e-4, "bilinear");
}

std::string obj_quad_with_uvs(const std::string& dir) {
  // A unit square in z = 0 made of two triangles, with UVs that repeat the texture twice in u.
  std::string path = dir + "/quad.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                         "vt 0 0\nvt 2 0\nvt 2 1\nvt 0 1\n"
                         "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
  return path;
}

TEST(TextureAlbedo, MeshUvsInterpolateAndRepeat) {
  std::string dir = testing::temp_dir();
  Image img = distinct_4x4();
  std::string tex = write_pfm(dir, "t.pfm", img);
  std::string obj = obj_quad_with_uvs(dir);
  std::string scene = "screen 8 4\ncamera 0.5 0.5 10 0.05\nbrdf 1 1 1 0 0 0 0\ntexture \"" + tex +
                      "\"\nmesh \"" + obj + "\" 0 0 0 1\n";
  auto p = parse_scene(scene, dir + "/quad.scn");
  ASSERT_TRUE(p.ok()) << ::testing::PrintToString(errors(p));
  EXPECT_TRUE(p.scene.table<Triangle>().has_uv());
  Bvh bvh = build_bvh_and_reorder(p.scene);
  Tracer tracer(p.scene, bvh, TracerBackend::kPacket);
  // ry = 0.05 at distance 10 frames y in [0, 1] and (aspect 2) x in [−0.5, 1.5]: the quad
  // covers pixels 2..5 of each row.
  Image out = render_raycast(tracer, RaycastMode::kAlbedo);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 2; x < 6; ++x) {
      // Pixel x's centre has u = 2·(x − 2 + 0.5)/4 (the UVs double u): compare with the lookup.
      double u = 2 * (x - 2 + 0.5) / 4, v = (3 - y + 0.5) / 4;
      expect_near(glm::dvec3(out.at(x, y)), texture_lookup(img, u, v), 1e-4, "quad pixel");
    }
  EXPECT_EQ(out.at(0, 0), glm::vec3(0, 0, 0));  // off the quad: a miss
}

TEST(TextureCommand, NeedsAMaterialAndAReadableImage) {
  std::string dir = testing::temp_dir();
  std::string tex = write_pfm(dir, "t.pfm", distinct_4x4());
  auto before = testing::parse(std::string(testing::kCameraLine) + "texture \"" + tex + "\"\n");
  ASSERT_EQ(errors(before).size(), 1u);
  EXPECT_THAT(errors(before)[0], ::testing::HasSubstr("t.scn:2:1: texture before any material"));
  auto missing = testing::parse(std::string(testing::kCameraLine) +
                                "brdf 1 1 1 0 0 0 0\ntexture nothere.png\n");
  ASSERT_EQ(errors(missing).size(), 1u);
  EXPECT_THAT(errors(missing)[0],
              ::testing::HasSubstr("t.scn:3:9: texture 'nothere.png' not found"));
  std::string bad = dir + "/bad.png";
  std::ofstream(bad) << "\x89PNG\r\n\x1a\ntruncated";
  auto unreadable =
      testing::parse(std::string(testing::kCameraLine) + "light 1 1 1\ntexture \"" + bad + "\"\n");
  ASSERT_EQ(errors(unreadable).size(), 1u);
  EXPECT_THAT(errors(unreadable)[0], ::testing::HasSubstr("bad.png"));
  auto extra = testing::parse(std::string(testing::kCameraLine) +
                              "brdf 1 1 1 0 0 0 0\ntexture a.png b.png\n");
  ASSERT_EQ(errors(extra).size(), 1u);
  EXPECT_THAT(errors(extra)[0], ::testing::HasSubstr("texture takes one file name"));
}

TEST(TextureCommand, AppliesToTheMaterialBeforeAndAfterAndOnceEachFile) {
  std::string dir = testing::temp_dir();
  std::string a = write_pfm(dir, "a.pfm", distinct_4x4());
  std::string b = write_pfm(dir, "b.pfm", Image(2, 2));
  auto p = testing::parse(std::string(testing::kCameraLine) + "screen 4 4\nbrdf 1 1 1 0 0 0 0\n" +
                          "sphere 0 0 0 1\ntexture \"" + a + "\"\nsphere 3 0 0 1\n" + "texture \"" +
                          b + "\"\nbrdf 0.5 0.5 0.5 0 0 0 0\ntexture \"" + a +
                          "\"\nsphere 6 0 0 1\nbrdf 1 1 1 0 0 0 0\nsphere 9 0 0 1\n");
  ASSERT_TRUE(p.ok()) << ::testing::PrintToString(errors(p));
  ASSERT_EQ(warnings(p).size(), 1u);  // the second texture on the first material
  EXPECT_THAT(warnings(p)[0], ::testing::HasSubstr("t.scn:7:1: warning: the material already has"));
  const auto& m = p.scene.materials;
  const SphereTable& s = p.scene.table<Sphere>();
  EXPECT_EQ(m[s.material[0]].texture, m[s.material[1]].texture);  // before and after the line
  EXPECT_EQ(p.scene.textures[m[s.material[0]].texture].file, b);  // the second one wins
  EXPECT_EQ(p.scene.textures[m[s.material[2]].texture].file, a);
  EXPECT_EQ(m[s.material[3]].texture, -1);  // a later brdf line starts untextured
  EXPECT_EQ(p.scene.textures.size(), 2u);   // a.pfm read once
}

TEST(TextureCommand, UvColumnsOnlyWhenATexturedMaterialUsesThem) {
  std::string dir = testing::temp_dir();
  std::string obj = obj_quad_with_uvs(dir);
  auto plain = testing::parse(std::string(testing::kCameraLine) + "brdf 1 1 1 0 0 0 0\nmesh \"" +
                              obj + "\" 0 0 0 1\n");
  ASSERT_TRUE(plain.ok());
  EXPECT_FALSE(plain.scene.table<Triangle>().has_uv());
  EXPECT_TRUE(plain.scene.table<Triangle>().t0u.empty());
  // A textured material on a mesh without UVs: a warning naming the mesh line.
  std::string tex = write_pfm(dir, "t.pfm", distinct_4x4());
  std::string flat = dir + "/flat.obj";
  std::ofstream(flat) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n";
  auto no_uv =
      testing::parse(std::string(testing::kCameraLine) + "screen 4 4\nbrdf 1 1 1 0 0 0 0\nmesh \"" +
                     flat + "\" 0 0 0 1\ntexture \"" + tex + "\"\n");
  ASSERT_TRUE(no_uv.ok());
  ASSERT_EQ(warnings(no_uv).size(), 1u);
  EXPECT_THAT(warnings(no_uv)[0], ::testing::HasSubstr("t.scn:4: warning: mesh"));
  EXPECT_THAT(warnings(no_uv)[0], ::testing::HasSubstr("no texture coordinates"));
}

}  // namespace
}  // namespace raylane
