// Ray-casting views: every tracer and instruction set renders the same picture.
#include <gtest/gtest.h>
#include <omp.h>

#include "raylane/image/metrics.h"
#include "raylane/render/raycast.h"
#include "raylane/scene/parser.h"
#include "support/paths.h"

namespace raylane {
namespace {

struct Rendered {
  Image image;
  RaycastStats stats;
};

Rendered render(const std::string& scene_name, RaycastMode mode, TracerBackend kind, Isa isa) {
  auto p = load_scene_file(testing::source_path("scenes/" + scene_name));
  EXPECT_TRUE(p.ok());
  Bvh bvh = build_bvh_and_reorder(p.scene);
  Tracer tracer(p.scene, bvh, kind, isa);
  Rendered r;
  r.image = render_raycast(tracer, mode, &r.stats);
  return r;
}

int differing_pixels(const Image& a, const Image& b) {
  int n = 0;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x)
      n += a.at(x, y) != b.at(x, y);
  return n;
}

// Pixels whose channels differ by more than 1 % of the pixel's value (plus 1e-3).
int visibly_differing_pixels(const Image& a, const Image& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.rgb.size(); i += 3) {
    bool differ = false;
    for (int k = 0; k < 3; ++k)
      differ |= std::abs(a.rgb[i + k] - b.rgb[i + k]) > 0.01f * std::abs(b.rgb[i + k]) + 1e-3f;
    n += differ;
  }
  return n;
}

// `--mode id`: the same primitive in every pixel for every tracer and ISA, except where two
// coplanar triangles overlap (letter X's two quads cross in one plane: either is right,
// and float and double t break the tie differently). Bound: 1 pixel in 10^4.
TEST(Raycast, IdImageIsTheSameForEveryTracerAndIsa) {
  Image ref = render("testscene.scn", RaycastMode::kId, TracerBackend::kScalar, Isa::kSse42).image;
  EXPECT_EQ(
      differing_pixels(
          ref, render("testscene.scn", RaycastMode::kId, TracerBackend::kBvh, Isa::kSse42).image),
      0);
  for (Isa isa : supported_isas()) {
    Image img = render("testscene.scn", RaycastMode::kId, TracerBackend::kPacket, isa).image;
    EXPECT_LE(differing_pixels(ref, img), 12) << isa_name(isa);
  }
}

// The lit view traces shadow rays through the same tracer; packet and scalar agree.
TEST(Raycast, LitImageAgreesAcrossTracers) {
  Rendered scalar = render("testscene.scn", RaycastMode::kLit, TracerBackend::kScalar, Isa::kSse42);
  Rendered packet = render("testscene.scn", RaycastMode::kLit, TracerBackend::kPacket, best_isa());
  EXPECT_GT(scalar.stats.shadow_rays, 100000u);
  EXPECT_EQ(scalar.stats.shadow_rays, packet.stats.shadow_rays);
  auto d = compare(packet.image, scalar.image);
  ASSERT_TRUE(d);
  // Float and double hit points differ in their last bits everywhere; visibly, only at
  // shadow and silhouette edges: at most 0.05 % of the pixels.
  EXPECT_LE(visibly_differing_pixels(packet.image, scalar.image), 60);
  EXPECT_LT(d->rmse, 0.02);
  // Direct light reaches the floor: the lit mean is far above the ambient-only level.
  EXPECT_GT(mean(scalar.image).x, 0.5);
}

// The views run their bands of rows on the threads; each band writes only its own pixels, so
// the image is the same for any number of threads, bit for bit.
TEST(Raycast, ImageIsTheSameForAnyThreadCount) {
  const int threads = omp_get_max_threads();
  for (RaycastMode mode : {RaycastMode::kLit, RaycastMode::kNormal}) {
    omp_set_num_threads(1);
    Rendered one = render("testscene.scn", mode, TracerBackend::kPacket, best_isa());
    omp_set_num_threads(3);
    Rendered three = render("testscene.scn", mode, TracerBackend::kPacket, best_isa());
    EXPECT_EQ(one.image.rgb, three.image.rgb) << raycast_mode_name(mode);
    EXPECT_EQ(one.stats.shadow_rays, three.stats.shadow_rays);
    EXPECT_GT(one.stats.camera_rays, 0u);
  }
  omp_set_num_threads(threads);
}

// PNG views of depth and id (they were once all white, or two flat colours): depth spans
// 0.1 … 1 over the hits, ids get colours that tell neighbouring rows apart, misses stay black.
TEST(Raycast, DepthAndIdAreMappedForViewing) {
  Image depth(3, 1);
  depth.set(0, 0, glm::vec3(2, 2, 2));
  depth.set(1, 0, glm::vec3(12, 12, 12));
  Image d = viewable(depth, RaycastMode::kDepth);
  EXPECT_EQ(d.at(0, 0), glm::vec3(1, 1, 1));
  EXPECT_NEAR(d.at(1, 0).x, 0.1f, 1e-6f);
  EXPECT_EQ(d.at(2, 0), glm::vec3(0, 0, 0));
  Image id(3, 1);
  id.set(0, 0, glm::vec3(4, 7, 0));
  id.set(1, 0, glm::vec3(4, 8, 0));
  Image v = viewable(id, RaycastMode::kId);
  EXPECT_NE(v.at(0, 0), v.at(1, 0));
  for (float c : {v.at(0, 0).x, v.at(0, 0).y, v.at(0, 0).z})
    EXPECT_GE(c, 0.2f);
  EXPECT_EQ(v.at(2, 0), glm::vec3(0, 0, 0));
  Image normal = viewable(id, RaycastMode::kNormal);
  EXPECT_EQ(normal.rgb, id.rgb);
}

TEST(Raycast, ImageIsUpright) {
  // The test scene's floor fills the bottom rows, the walls the top rows: in the normal view
  // the floor's +z normal is (0.5, 0.5, 1).
  Image img =
      render("testscene.scn", RaycastMode::kNormal, TracerBackend::kPacket, best_isa()).image;
  glm::vec3 bottom = img.at(10, img.height - 2);
  EXPECT_NEAR(bottom.z, 1.0f, 1e-3f);
  EXPECT_NEAR(bottom.x, 0.5f, 1e-3f);
  glm::vec3 top = img.at(10, 1);
  EXPECT_LT(top.z, 0.9f);  // a wall
}

TEST(Raycast, DepthIsTheHitDistance) {
  Image img = render("sphere.scn", RaycastMode::kDepth, TracerBackend::kPacket, best_isa()).image;
  // The centre pixel looks along +y at the unit sphere at the origin from (0, −6, 0).
  glm::vec3 c = img.at(img.width / 2, img.height / 2);
  EXPECT_NEAR(c.x, 5.0f, 1e-3f);
  EXPECT_EQ(img.at(0, 0), glm::vec3(0, 0, 0));  // a miss
}

}  // namespace
}  // namespace raylane
