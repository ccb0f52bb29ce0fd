// Checkpoints of the path tracer's film: a render continued from a saved film is the render
// an uninterrupted run gives, bit for bit; films are refused for another scene or settings.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <filesystem>
#include <fstream>

#include "raylane/image/metrics.h"
#include "raylane/render/film/film.h"
#include "raylane/scene/parser.h"
#include "support/paths.h"

namespace raylane {
namespace {

struct Rendered {
  Scene scene;
  Bvh bvh;
};

Rendered load(const char* name) {
  auto p = load_scene_file(testing::source_path(std::string("scenes/") + name));
  EXPECT_TRUE(p.ok());
  Rendered r{std::move(p.scene), {}};
  r.bvh = build_bvh_and_reorder(r.scene);
  return r;
}

PathSettings settings(int spp) {
  PathSettings s;
  s.spp = spp;
  s.seed = 7;
  return s;
}

TEST(Film, IdentifyingAFilmGivesTheFingerprintAndOriginOfItsSettings) {
  Rendered r = load("sphere.scn");
  PathSettings s = settings(3);
  s.seed = 11, s.max_depth = 4;
  Film film;
  identify_film(film, r.scene, s);
  EXPECT_EQ(film.fingerprint, film_fingerprint(r.scene, s));
  const FilmOrigin want = film_origin(r.scene, s);
  EXPECT_TRUE(film.origin.known);
  EXPECT_EQ(film.origin.scene, want.scene);
  EXPECT_EQ(film.origin.scene, scene_fingerprint(r.scene));
  EXPECT_EQ(film.origin.seed, 11u);
  EXPECT_EQ(film.origin.max_depth, 4);
  EXPECT_EQ(origin_difference(film.origin, want), "");
}

// A render without a film to save leaves the film's identity alone: the fingerprint's pass
// over the scene is paid only by --checkpoint and --resume.
TEST(Film, RenderingDoesNotIdentifyTheFilm) {
  Rendered r = load("sphere.scn");
  Tracer tracer(r.scene, r.bvh, TracerBackend::kPacket);
  Film film;
  render_path(tracer, settings(1), nullptr, &film);
  EXPECT_EQ(film.fingerprint, 0u);
  EXPECT_FALSE(film.origin.known);
}

TEST(Film, ResumedRenderIsTheUninterruptedRender) {
  Rendered r = load("sphere.scn");
  Tracer tracer(r.scene, r.bvh, TracerBackend::kPacket);
  Image whole = render_path(tracer, settings(5));

  Film film;
  identify_film(film, r.scene, settings(2));  // the CLI's --checkpoint does this
  render_path(tracer, settings(2), nullptr, &film);
  EXPECT_EQ(film.passes, 2);
  std::string path = testing::temp_dir() + "/a.film";
  ASSERT_TRUE(save_film(path, film).ok());
  auto loaded = load_film(path);
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  EXPECT_EQ(loaded->fingerprint, film_fingerprint(r.scene, settings(5)));
  EXPECT_EQ(loaded->origin.sampler, int32_t(settings(5).sampler));
  EXPECT_EQ(loaded->origin.shading, int32_t(settings(5).shading));
  PathStats stats;
  Image resumed = render_path(tracer, settings(5), &stats, &*loaded);
  EXPECT_EQ(stats.passes, 5);
  EXPECT_EQ(loaded->passes, 5);
  EXPECT_EQ(resumed.rgb, whole.rgb);  // bit for bit
  EXPECT_GT(mean(resumed).x, 0.0);    // not a black image
}

TEST(Film, FingerprintFollowsWhatShapesTheSamples) {
  Rendered r = load("sphere.scn");
  uint64_t base = film_fingerprint(r.scene, settings(4));
  EXPECT_EQ(film_fingerprint(r.scene, settings(400)), base);  // spp only counts passes
  PathSettings s = settings(4);
  s.time_limit = 3;
  EXPECT_EQ(film_fingerprint(r.scene, s), base);
  for (auto change :
       {+[](PathSettings& p) { p.seed = 8; },
        +[](PathSettings& p) { p.integrator = Integrator::kNee; },
        +[](PathSettings& p) { p.max_depth = 5; },
        +[](PathSettings& p) {
          p.sampler = p.sampler == Sampler::kSobol ? Sampler::kMt19937 : Sampler::kSobol;
        },
        +[](PathSettings& p) {
          p.shading = p.shading == Shading::kFloat ? Shading::kDouble : Shading::kFloat;
        }}) {
    PathSettings t = settings(4);
    change(t);
    EXPECT_NE(film_fingerprint(r.scene, t), base);
  }
  Rendered other = load("box.scn");
  EXPECT_NE(film_fingerprint(other.scene, settings(4)), base);
  r.scene.materials[0].kd.x += 0.125f;
  EXPECT_NE(film_fingerprint(r.scene, settings(4)), base);
}

TEST(Film, HostileFilmFilesAreErrors) {
  std::string dir = testing::temp_dir();
  Film f{2, 1, 3, std::vector<double>(6, 0.5), 42, {}, {}, {}, {}};
  ASSERT_TRUE(save_film(dir + "/ok.film", f).ok());
  auto ok = load_film(dir + "/ok.film");
  ASSERT_TRUE(ok.ok()) << ok.error();
  EXPECT_EQ(ok->sum, f.sum);
  EXPECT_EQ(ok->passes, 3);

  std::filesystem::copy_file(dir + "/ok.film", dir + "/short.film");
  std::filesystem::resize_file(dir + "/short.film", 80);
  auto short_file = load_film(dir + "/short.film");
  ASSERT_FALSE(short_file.ok());
  EXPECT_NE(short_file.error().find("a 2x1 film has 112 bytes, the file has 80"), std::string::npos)
      << short_file.error();

  // 2^40 pixels announced, 32 bytes present.
  Film huge{1u << 20, 1u << 20, 1, {}, 0, {}, {}, {}, {}};
  ASSERT_TRUE(save_film(dir + "/huge.film", huge).ok());
  auto h = load_film(dir + "/huge.film");
  ASSERT_FALSE(h.ok());
  EXPECT_NE(h.error().find("1 … 2^28 pixels"), std::string::npos) << h.error();

  std::ofstream(dir + "/text.film") << "this is not a film, but it is long enough to have a header";
  EXPECT_FALSE(load_film(dir + "/text.film").ok());
  EXPECT_FALSE(load_film(dir + "/missing.film").ok());

  // A film of the first format (a 32-byte header, no origin) is still read.
  std::string v1("RLFILM1\0", 8);
  for (uint32_t w : {2u, 1u, 3u, 0u})
    v1.append(reinterpret_cast<const char*>(&w), 4);
  uint64_t fp = 42;
  v1.append(reinterpret_cast<const char*>(&fp), 8);
  v1.append(reinterpret_cast<const char*>(f.sum.data()), 48);
  std::ofstream(dir + "/v1.film", std::ios::binary) << v1;
  auto old = load_film(dir + "/v1.film");
  ASSERT_TRUE(old.ok()) << old.error();
  EXPECT_EQ(old->sum, f.sum);
  EXPECT_EQ(old->fingerprint, 42u);
  EXPECT_FALSE(old->origin.known);

  // The origin's enums out of range: named in messages, so refused before anything indexes
  // their names with them.
  for (int field : {0, 1, 2}) {
    Film damaged = f;
    damaged.origin.known = true;
    damaged.origin.integrator = damaged.origin.sampler = damaged.origin.shading = 0;
    int32_t* words[] = {&damaged.origin.integrator, &damaged.origin.sampler,
                        &damaged.origin.shading};
    *words[field] = 7;
    ASSERT_TRUE(save_film(dir + "/enum.film", damaged).ok());
    auto e = load_film(dir + "/enum.film");
    ASSERT_FALSE(e.ok());
    const char* expected[] = {"found 7, 0 and 0", "found 0, 7 and 0", "found 0, 0 and 7"};
    EXPECT_NE(e.error().find(expected[field]), std::string::npos) << e.error();
  }

  // Non-finite sums: damage that a resumed render would spread into its image.
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    Film damaged = f;
    damaged.sum[4] = bad;
    ASSERT_TRUE(save_film(dir + "/nan.film", damaged).ok());
    auto n = load_film(dir + "/nan.film");
    ASSERT_FALSE(n.ok());
    EXPECT_NE(n.error().find("pixel 1 holds a non-finite sum"), std::string::npos) << n.error();
  }
}

}  // namespace
}  // namespace raylane
