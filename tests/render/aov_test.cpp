// AOVs of the path render (render/film/aov.h; docs/scene-language.md, "AOVs: albedo, normal, depth,
// position"): summed at the colour's samples, equal to the ray-cast views where a pixel sees one
// surface, carried by a resumed film bit for bit, and independent of the thread count.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "raylane/bvh/bvh.h"
#include "raylane/render/film/film.h"
#include "raylane/render/raycast.h"
#include "raylane/scene/parser.h"
#include "support/paths.h"

namespace raylane {
namespace {

struct Loaded {
  Scene scene;
  Bvh bvh;
};

// The course scene at 80×60 (or `scale` times that): small enough for a unit test, large
// enough for interiors.
Loaded course_scene(int scale = 1) {
  ParseOptions opts;
  opts.overrides = {"screen " + std::to_string(80 * scale) + " " + std::to_string(60 * scale)};
  auto p = load_scene_file(testing::source_path("scenes/testscene.scn"), opts);
  EXPECT_TRUE(p.ok());
  Loaded l{std::move(p.scene), {}};
  l.bvh = build_bvh_and_reorder(l.scene);
  return l;
}

PathSettings with_aovs(int spp, const char* list) {
  PathSettings s;
  s.spp = spp;
  s.seed = 3;
  s.aovs = *parse_aov_list(list);
  return s;
}

// Pixels of the 80×60 image that see one primitive: `--mode id` at 4× the resolution meets
// the same primitive at the 6×6 sub-pixel centres that cover the pixel and a quarter pixel
// around it, so the jittered samples inside it meet that primitive too (unless something
// thinner than a quarter pixel crosses it, which the course scene does not hold).
std::vector<std::size_t> interior_pixels(const Image& fine_id) {
  std::vector<std::size_t> out;
  for (uint32_t y = 1; y + 1 < 60; ++y)
    for (uint32_t x = 1; x + 1 < 80; ++x) {
      const glm::vec3 first = fine_id.at(4 * x - 1, 4 * y - 1);
      bool same = first.x > 0;  // a hit
      for (uint32_t fy = 4 * y - 1; fy <= 4 * y + 4; ++fy)
        for (uint32_t fx = 4 * x - 1; fx <= 4 * x + 4; ++fx)
          same = same && fine_id.at(fx, fy) == first;
      if (same) out.push_back(std::size_t(y) * 80 + x);
    }
  return out;
}

// The mean of N equal doubles is that value within N·2^-53 relatively, then rounded to
// float: within one float ulp (2^-23 relatively) of the ray-cast view's float.
TEST(Aov, AlbedoEqualsTheRayCastAlbedoWhereAPixelSeesOneSurface) {
  Loaded l = course_scene();
  Tracer tracer(l.scene, l.bvh, TracerBackend::kPacket);
  Film film;
  render_path(tracer, with_aovs(4, "albedo,depth"), nullptr, &film);
  const Image albedo = film.aov_image(Aov::kAlbedo);
  const Image reference = render_raycast(tracer, RaycastMode::kAlbedo);
  Loaded fine = course_scene(4);
  const auto interior = interior_pixels(
      render_raycast(Tracer(fine.scene, fine.bvh, TracerBackend::kPacket), RaycastMode::kId));
  ASSERT_GT(interior.size(), std::size_t(80 * 60 / 2));
  for (std::size_t p : interior)
    for (int k = 0; k < 3; ++k) {
      float want = reference.rgb[p * 3 + k], got = albedo.rgb[p * 3 + k];
      EXPECT_NEAR(got, want, std::ldexp(std::abs(want), -23)) << "pixel " << p;
    }
  // Where a pixel's samples meet different surfaces, it is their average: the edges of the
  // pink sphere against the green wall hold values no single surface has.
  std::size_t mixed = 0;
  for (std::size_t p = 0; p < std::size_t(80 * 60); ++p) {
    bool any_equal = false;
    for (uint32_t q = 0; q < 80 * 60; q += 7)
      any_equal = any_equal || (reference.rgb[q * 3] == albedo.rgb[p * 3] &&
                                reference.rgb[q * 3 + 1] == albedo.rgb[p * 3 + 1]);
    mixed += !any_equal;
  }
  EXPECT_GT(mixed, 20u);
}

TEST(Aov, ResumedFilmCarriesItsAovsBitForBit) {
  Loaded l = course_scene();
  Tracer tracer(l.scene, l.bvh, TracerBackend::kPacket);
  const PathSettings four = with_aovs(4, "albedo,normal,depth,position");
  Film whole;
  render_path(tracer, four, nullptr, &whole);

  Film part;
  render_path(tracer, with_aovs(2, "albedo,normal,depth,position"), nullptr, &part);
  std::string path = testing::temp_dir() + "/aov.film";
  ASSERT_TRUE(save_film(path, part).ok());
  auto loaded = load_film(path);
  ASSERT_TRUE(loaded) << loaded.error();
  EXPECT_EQ(loaded->aovs, four.aovs);
  render_path(tracer, four, nullptr, &*loaded);
  EXPECT_EQ(loaded->aov_sum, whole.aov_sum);  // bit for bit
  EXPECT_EQ(loaded->sum, whole.sum);
}

TEST(Aov, SumsDoNotDependOnTheThreadCount) {
  Loaded l = course_scene();
  Tracer tracer(l.scene, l.bvh, TracerBackend::kPacket);
  const int threads = omp_get_max_threads();
  Film one, many;
  omp_set_num_threads(1);
  render_path(tracer, with_aovs(2, "normal,position"), nullptr, &one);
  omp_set_num_threads(std::max(2, threads));
  render_path(tracer, with_aovs(2, "normal,position"), nullptr, &many);
  omp_set_num_threads(threads);
  EXPECT_EQ(one.aov_sum, many.aov_sum);
  // Averages of unit normals: never longer than 1.
  const Image n = one.aov_image(Aov::kNormal);
  for (std::size_t p = 0; p < std::size_t(n.width) * n.height; ++p)
    EXPECT_LE(length(glm::dvec3(n.rgb[p * 3], n.rgb[p * 3 + 1], n.rgb[p * 3 + 2])), 1.0 + 1e-6);
}

TEST(Aov, DamagedAovPartOfAFilmIsAnError) {
  Loaded l = course_scene();
  Tracer tracer(l.scene, l.bvh, TracerBackend::kPacket);
  Film film;
  render_path(tracer, with_aovs(1, "depth"), nullptr, &film);
  std::string path = testing::temp_dir() + "/short.film";
  film.aov_sum.pop_back();  // one sum short
  ASSERT_TRUE(save_film(path, film).ok());
  auto loaded = load_film(path);
  ASSERT_FALSE(loaded);
  EXPECT_NE(loaded.error().find("its AOVs (depth) take"), std::string::npos) << loaded.error();

  film.aov_sum.push_back(std::nan(""));  // the last pixel's depth sum damaged
  ASSERT_TRUE(save_film(path, film).ok());
  auto nan = load_film(path);
  ASSERT_FALSE(nan);
  EXPECT_NE(nan.error().find(": pixel 4799 holds a non-finite AOV sum (nan)"), std::string::npos)
      << nan.error();
}

TEST(Aov, ListsAreParsedStrictly) {
  EXPECT_EQ(parse_aov_list("normal,albedo")->bits, 3u);
  EXPECT_EQ(parse_aov_list("albedo,normal,depth,position")->channels(), 10);
  EXPECT_EQ(parse_aov_list("depth,position")->offset(Aov::kPosition), 1);
  for (const char* bad : {"", "albedo,", "albedo,albedo", "Albedo", "albedo normal"})
    EXPECT_FALSE(parse_aov_list(bad)) << bad;
}

}  // namespace
}  // namespace raylane
