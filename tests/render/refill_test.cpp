// Wavefronts that refill (src/render/wavefront/render_loop.h): with the Sobol sampler a
// thread's wavefront takes the next tile's camera rays while paths of the tiles before are
// still going, so one step shades vertices of several depths. Every number a path draws comes
// from its pixel, pass and depth, so the image must be the one rendered tile by tile, bit for
// bit: the colour and the AOVs, with either shading, every integrator, roulette from the first
// bounce, glass (both vertex queues in one step) and motion blur (the paths' times, moving
// lights sampled at them).
#include <gtest/gtest.h>
#include <omp.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "raylane/bvh/bvh.h"
#include "raylane/core/strings.h"
#include "raylane/render/film/film.h"
#include "raylane/render/path.h"
#include "raylane/scene/parser.h"
#include "support/paths.h"

namespace raylane {
namespace {

struct Rendered {
  Film film;
  PathStats stats;
};

// The scene at 80×48 (5×3 tiles of 16²), rendered with `s` on `threads` threads.
Rendered render_at(const std::string& file, PathSettings s, int threads) {
  auto p = load_scene_file(testing::source_path(file));
  EXPECT_TRUE(p.ok()) << file;
  Scene& scene = p.scene;
  scene.width = 80, scene.height = 48;
  Bvh bvh = build_bvh_and_reorder(scene);
  Tracer tracer(scene, bvh, TracerBackend::kPacket);
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  Rendered r;
  render_path(tracer, s, &r.stats, &r.film);
  omp_set_num_threads(before);
  return r;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  // (memcmp of two empty vectors' data() would pass it null pointers.)
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

struct Case {
  std::string file;
  Shading shading = Shading::kFloat;
  Integrator integrator = Integrator::kMis;
  int rr_depth = 3;
  bool aovs = false;
};

TEST(WavefrontRefill, TheImageIsTheTileByTileImageBitForBit) {
  const Case cases[] = {
      {"scenes/testscene.scn"},
      {"scenes/testscene.scn", Shading::kDouble},
      {"scenes/testscene.scn", Shading::kFloat, Integrator::kNee, 1},
      {"scenes/testscene.scn", Shading::kFloat, Integrator::kBrdf},
      {"scenes/testscene.scn", Shading::kFloat, Integrator::kMis, 3, true},
      {"scenes/testscene-glass.scn", Shading::kFloat, Integrator::kMis, 1},
      {"scenes/testscene-textured.scn"},
      {"scenes/motion-blur.scn"},
      {"scenes/motion-blur-light.scn"},  // lights sampled at each path's time
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(cat(c.file, " ", shading_name(c.shading), " ", integrator_name(c.integrator),
                     " rr ", c.rr_depth, c.aovs ? " aovs" : ""));
    PathSettings s;
    s.sampler = Sampler::kSobol, s.spp = 2, s.seed = 5;
    s.shading = c.shading, s.integrator = c.integrator, s.rr_depth = c.rr_depth;
    if (c.aovs) s.aovs.bits = (1u << kAovCount) - 1;  // every AOV
    s.refill = false;
    const Rendered tile_by_tile = render_at(c.file, s, 1);
    s.refill = true;
    for (int threads : {1, 2}) {
      const Rendered refilled = render_at(c.file, s, threads);
      EXPECT_TRUE(same_bits(refilled.film.sum, tile_by_tile.film.sum)) << threads << " threads";
      EXPECT_TRUE(same_bits(refilled.film.aov_sum, tile_by_tile.film.aov_sum))
          << threads << " threads";
      EXPECT_EQ(refilled.stats.rays(), tile_by_tile.stats.rays());
    }
    // The wavefronts did refill: paths of a tile's long tail shared their steps with the next
    // tiles', so the same rays took far fewer steps than tile by tile.
    const Rendered one = render_at(c.file, s, 1);
    std::printf("%s: %llu steps refilled, %llu tile by tile, for %llu rays\n", c.file.c_str(),
                (unsigned long long)one.stats.steps, (unsigned long long)tile_by_tile.stats.steps,
                (unsigned long long)one.stats.rays());
    EXPECT_LT(double(one.stats.steps), 0.7 * double(tile_by_tile.stats.steps))
        << one.stats.steps << " steps refilled, " << tile_by_tile.stats.steps << " tile by tile";
  }
}

// MT19937 draws in the order of one tile's rows, so its wavefronts never refill: the setting
// changes nothing, not even the number of steps.
TEST(WavefrontRefill, Mt19937RendersTileByTileEither) {
  PathSettings s;
  s.sampler = Sampler::kMt19937, s.spp = 2, s.seed = 5;
  s.refill = false;
  const Rendered off = render_at("scenes/testscene.scn", s, 1);
  s.refill = true;
  const Rendered on = render_at("scenes/testscene.scn", s, 1);
  EXPECT_TRUE(same_bits(on.film.sum, off.film.sum));
  EXPECT_EQ(on.stats.steps, off.stats.steps);
}

}  // namespace
}  // namespace raylane
