// The path tracer against analytic answers (docs/hard-cases.md M1, M3): a furnace with a known
// radiance, direct light from a sphere on a plane; and determinism across thread counts.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <vector>

#include "raylane/bvh/bvh.h"
#include "raylane/core/strings.h"
#include "raylane/render/materials/shade_lanes.h"
#include "raylane/render/path.h"
#include "raylane/scene/parser.h"
#include "support/paths.h"

namespace raylane {
namespace {

struct PixelStats {
  double mean = 0, sigma = 0;  // mean of the pixels (channel 0) and its standard error
};

// Pixels whose expectation is the same number are independent estimates of it, so the
// spread of the pixel values gives the estimate's own standard error.
PixelStats pixel_stats(const Image& img) {
  double s = 0, s2 = 0;
  std::size_t n = std::size_t(img.width) * img.height;
  for (std::size_t i = 0; i < n; ++i) {
    double v = img.rgb[i * 3];
    s += v, s2 += v * v;
  }
  double mean = s / n;
  return {mean, std::sqrt(std::max(0.0, s2 / n - mean * mean) / (n - 1))};
}

Image render(Scene& scene, const PathSettings& settings, PathStats* stats = nullptr) {
  Bvh bvh = build_bvh_and_reorder(scene);
  Tracer tracer(scene, bvh, TracerBackend::kPacket);
  return render_path(tracer, settings, stats);
}

Scene parse(const std::string& text) {
  auto p = parse_scene(text, "test.scn");
  EXPECT_TRUE(p.ok());
  return std::move(p.scene);
}

// A closed diffuse sphere (radius R = 1, Kd = ρ = 0.5, not emitting, seen from inside) around
// a sphere light of radius a = 0.5 and radiance Le = 5 at its centre. By symmetry every wall
// point leaves the same radiance L, and a wall point sees the light at normal incidence with
// projected solid angle π·s², s = a/R, and the wall elsewhere (the light reflects nothing):
//   L = (ρ/π)·(π·Le·s² + π·L·(1 − s²))  ⇒  L = ρ·Le·s² / (1 − ρ·(1 − s²)) = 0.625/0.625 = 1.
// The camera sits between light and wall, looking away from the light.
constexpr const char* kFurnace =
    "screen 16 16\ncamera 0 0 0.7 0.3 x 180\n"
    "brdf 0.5 0.5 0.5 0 0 0 1\nsphere 0 0 0 1\nlight 5 5 5\nsphere 0 0 0 0.5\n";

constexpr Sampler kSamplers[] = {Sampler::kMt19937, Sampler::kSobol};
constexpr Shading kShadings[] = {Shading::kDouble, Shading::kFloat};

// Each pixel is an independent estimate for either sampler (Sobol scrambles per pixel), so the
// spread over pixels gives the standard error of the mean.
TEST(PathTracer, FurnaceConvergesToTheAnalyticRadiance) {
  for (Shading shading : kShadings)
    for (Sampler sampler : kSamplers)
      for (Integrator integrator : {Integrator::kBrdf, Integrator::kNee, Integrator::kMis}) {
        Scene scene = parse(kFurnace);
        PathSettings s;
        s.integrator = integrator;
        s.sampler = sampler;
        s.shading = shading;
        s.spp = 64;
        s.seed = 5;
        PathStats stats;
        PixelStats p = pixel_stats(render(scene, s, &stats));
        std::string what = cat(integrator_name(integrator), "/", sampler_name(sampler), "/",
                               shading_name(shading));
        SCOPED_TRACE(what);
        std::printf("furnace %s: %.5f ± %.5f (expected 1)\n", what.c_str(), p.mean, p.sigma);
        EXPECT_NEAR(p.mean, 1.0, 4 * p.sigma);
        EXPECT_LT(p.sigma, 0.02);  // the test has power: 4σ well under the quantity tested
        EXPECT_EQ(stats.nonfinite_samples, 0u);
        EXPECT_EQ(stats.passes, 64);
      }
}

// The phase times (--stats) are thread-seconds: each is ≥ 0, and together they fit in the
// threads' wall time; light sampling, timed inside shading, is not counted twice.
TEST(PathTracer, PhaseTimesAddUpToNoMoreThanTheThreadsTime) {
  Scene scene = parse(kFurnace);
  PathSettings s;
  s.spp = 8;
  s.time_phases = true;
  PathStats stats;
  auto start = std::chrono::steady_clock::now();
  render(scene, s, &stats);
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const PathPhases& p = stats.phases;
  for (double t : {p.camera, p.trace_camera, p.trace_rest, p.shade, p.lights, p.film})
    EXPECT_GE(t, 0.0);
  EXPECT_GT(p.trace_camera, 0.0);
  EXPECT_GT(p.lights, 0.0);  // mis samples lights
  EXPECT_GT(p.total(), 0.0);
  EXPECT_LE(p.total(), wall * omp_get_max_threads());
  PathSettings off = s;
  off.time_phases = false;
  PathStats none;
  render(scene, off, &none);
  EXPECT_EQ(none.phases.total(), 0.0);
}

// Glass whose index matches the air (ior 1, and 1 ± 1e-6) bends nothing: a slab of it in front
// of an emitter passes the light straight through, attenuated by Beer's law only. A smooth
// lobe (α = 10^4) and Ks = 0 make Schlick's F vanish ((1 − cos θm)^5 < 1e-15) and G = 1 at
// near-normal incidence, and the weight's mean over the microfacets is exactly 1 per
// interface (E[cos θm] = (α+1)/(α+2)), so a camera ray through a slab of thickness 1 sees
// Le·Kt. Every integrator must find it: at η = 1 transmission is a Dirac lobe that light
// sampling cannot reach (it used to be black with nee and 1 % of Kt with mis).
TEST(PathTracer, IndexMatchedGlassPassesLightThroughAttenuatedByKt) {
  for (const char* ior : {"1", "1.000001", "0.999999"})
    for (Integrator integrator : {Integrator::kBrdf, Integrator::kNee, Integrator::kMis}) {
      SCOPED_TRACE(std::string("ior ") + ior + ", " + std::string(integrator_name(integrator)));
      Scene scene = parse(std::string("screen 16 16\ncamera 0 0 5 0.001\n") +
                          "brdf 0 0 0 0 0 0 10000 0.9 0.4 0.9 " + ior + "\n" +
                          "box -10 -10 1 20 20 1\nlight 1 1 1\nbox -50 -50 -5 100 100 1\n");
      PathSettings s;
      s.integrator = integrator;
      s.spp = 16;
      PathStats stats;
      PixelStats p = pixel_stats(render(scene, s, &stats));
      // Beyond the statistics: the ray offsets change the path inside the slab by a few
      // float roundoffs of the coordinates (~1e-6), which Beer's law turns into as much.
      EXPECT_NEAR(p.mean, 0.9, 4 * p.sigma + 1e-5);
      EXPECT_EQ(stats.nonfinite_samples, 0u);
    }
}

// Beer's law inside refracting glass (ior 1.5, which the float shading shades in lanes): two
// slabs side by side under the camera, 1 and 2 thick, Kt = (0.9, 0.5, 0.2). Every path from the
// camera crosses one slab (Ks = 0: no reflection to speak of) and gains a colour-blind weight
// times Kt^t per channel, t the distance inside, within 1e-4 of the thickness (the smooth lobe
// tilts the path by ~1/√α). So each pixel's channels stand as Kt's powers: G/R = (5/9)^t,
// B/R = (2/9)^t, to within 1e-4·t·|ln(Kt ratio)| ≈ 4e-4 relative, whatever the noise, and both
// thicknesses show. Without Beer's law the channels would be equal; on the wrong face, or with
// another row's distance, the powers would be wrong.
TEST(PathTracer, RefractingGlassColoursByBeersLaw) {
  Scene scene = parse(
      "screen 16 16\ncamera 0 0 5 0.001\nbrdf 0 0 0 0 0 0 10000 0.9 0.5 0.2 1.5\n"
      "box -10 -10 1 10 20 1\nbox 0 -10 0 10 20 2\nlight 1 1 1\nbox -50 -50 -5 100 100 1\n");
  for (Shading shading : kShadings)
    for (Integrator integrator : {Integrator::kBrdf, Integrator::kMis}) {
      SCOPED_TRACE(std::string(shading_name(shading)) + ", " +
                   std::string(integrator_name(integrator)));
      PathSettings s;
      s.shading = shading, s.integrator = integrator, s.spp = 4;
      Image img = render(scene, s);
      int seen[3] = {0, 0, 0};  // pixels through 1, through 2, neither
      for (std::size_t i = 0; i < img.rgb.size(); i += 3) {
        const double r = img.rgb[i], g = img.rgb[i + 1] / r, b = img.rgb[i + 2] / r;
        ASSERT_GT(r, 0.0) << "pixel " << i / 3;  // the light comes through
        int which = 2;
        for (int t : {1, 2})
          if (std::abs(g / std::pow(5.0 / 9, t) - 1) < 4e-4 &&
              std::abs(b / std::pow(2.0 / 9, t) - 1) < 4e-4)
            which = t - 1;
        ++seen[which];
      }
      EXPECT_GT(seen[0], 64);
      EXPECT_GT(seen[1], 64);
      EXPECT_LE(seen[2], 16);  // at most a column of pixels straddles the two slabs
    }
}

// How many of two images' values differ in their bits (all of them if the sizes differ).
std::size_t values_that_differ(const Image& a, const Image& b) {
  if (a.rgb.size() != b.rgb.size()) return std::max(a.rgb.size(), b.rgb.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i)
    differ += std::memcmp(&a.rgb[i], &b.rgb[i], sizeof(float)) != 0;
  return differ;
}

// Vertices on a black material end their path whether the lanes drop them (after their surfaces
// were computed, moving the rows behind them up with every column) or the double shading meets
// them (a textured material is shaded in double: a white texture keeps it black). Either way
// nothing else changes, so the two renders are the same bit for bit; a column the drop forgot
// to move would shade the rows behind a black one with another row's ray, distance or normal.
// The glass scene: Beer's law reads each row's distance, the offsets its ray.
TEST(PathTracer, BlackRowsDroppedFromTheLanesChangeNoOtherRow) {
  auto load = [](bool textured) {
    auto p = load_scene_file(testing::source_path("scenes/testscene-glass.scn"));
    EXPECT_TRUE(p.ok());
    Scene scene = std::move(p.scene);
    Image white(1, 1);
    white.rgb = {1, 1, 1};
    scene.textures.push_back(make_texture("white", white));
    int blackened = 0;
    for (Material& m : scene.materials)
      if (m.kd == glm::vec3(0.2f, 0.9f, 0.2f) || m.kd == glm::vec3(0.2f, 0.2f, 0.9f)) {
        m.kd = {0, 0, 0};
        if (textured) m.texture = int32_t(scene.textures.size() - 1);
        ++blackened;
      }
    EXPECT_EQ(blackened, 2);  // two walls
    return scene;
  };
  for (Sampler sampler : kSamplers) {
    SCOPED_TRACE(std::string(sampler_name(sampler)));
    PathSettings s;
    s.sampler = sampler, s.spp = 2, s.shading = Shading::kFloat;
    Scene in_lanes = load(false), in_double = load(true);
    EXPECT_EQ(values_that_differ(render(in_lanes, s), render(in_double, s)), 0u);
  }
}

// A scene whose lane materials are all diffuse alone draws no lobe number (its Sobol BSDF
// group computes components 0, 1 and roulette's 3): the same scene with an unused glossy
// material appended draws every number, and its image is the same bit for bit.
TEST(PathTracer, LeavingOutTheLobeNumberChangesNoImage) {
  auto load = [](bool glossy_too) {
    auto p = load_scene_file(testing::source_path("scenes/testscene.scn"));
    EXPECT_TRUE(p.ok());
    Scene scene = std::move(p.scene);
    if (glossy_too) {
      Material glossy;
      glossy.kd = {0.3f, 0.3f, 0.3f}, glossy.ks = {0.5f, 0.5f, 0.5f}, glossy.alpha = 40;
      scene.materials.push_back(glossy);
    }
    EXPECT_EQ(LaneMaterials(scene.materials).lobe_unread, !glossy_too);
    return scene;
  };
  PathSettings s;
  s.sampler = Sampler::kSobol, s.spp = 2, s.shading = Shading::kFloat, s.rr_depth = 2;
  Scene diffuse = load(false), mixed = load(true);
  EXPECT_EQ(values_that_differ(render(diffuse, s), render(mixed, s)), 0u);
}

// A diffuse plane (ρ = 0.5) under a sphere light of radius r = 0.5 and Le = 2 centred d = 3
// above the foot point: E = π·Le·(r/d)² (the sphere subtends sin²θmax = (r/d)² and sits on the
// normal), so the plane leaves L = ρ·E/π = ρ·Le·(r/d)² = 1/36 there. The camera looks
// straight down at the foot point through a tiny field of view.
constexpr const char* kDirect =
    "screen 16 16\ncamera 0 0 1 0.001\nbrdf 0.5 0.5 0.5 0 0 0 1\nbox -50 -50 -1 100 100 1\n"
    "light 2 2 2\nsphere 0 0 3 0.5\n";

TEST(PathTracer, DirectLightMatchesTheAnalyticIrradiance) {
  const double expected = 0.5 * 2 * (0.5 / 3) * (0.5 / 3);
  for (Shading shading : kShadings)
    for (Sampler sampler : kSamplers)
      for (Integrator integrator : {Integrator::kBrdf, Integrator::kNee, Integrator::kMis}) {
        Scene scene = parse(kDirect);
        PathSettings s;
        s.integrator = integrator;
        s.sampler = sampler;
        s.shading = shading;
        s.spp = integrator == Integrator::kBrdf ? 256 : 16;
        s.seed = 9;
        PathStats stats;
        PixelStats p = pixel_stats(render(scene, s, &stats));
        std::string what = cat(integrator_name(integrator), "/", sampler_name(sampler), "/",
                               shading_name(shading));
        std::printf("direct %s: %.6f ± %.6f (expected %.6f)\n", what.c_str(), p.mean, p.sigma,
                    expected);
        SCOPED_TRACE(what);
        EXPECT_NEAR(p.mean, expected, 4 * p.sigma);
        EXPECT_LT(p.sigma, 0.03 * expected);
        EXPECT_EQ(stats.nonfinite_samples, 0u);
      }
}

Image render_testscene(int threads, uint64_t seed, Sampler sampler,
                       Shading shading = Shading::kFloat) {
  auto p = load_scene_file(testing::source_path("scenes/testscene.scn"));
  EXPECT_TRUE(p.ok());
  p.scene.width = 48, p.scene.height = 36;
  PathSettings s;
  s.spp = 2;
  s.seed = seed;
  s.sampler = sampler;
  s.shading = shading;
  int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  Image img = render(p.scene, s);
  omp_set_num_threads(before);
  return img;
}

TEST(PathTracer, ImageIsTheSameForAnyThreadCount) {
  for (Shading shading : kShadings)
    for (Sampler sampler : kSamplers) {
      SCOPED_TRACE(cat(sampler_name(sampler), "/", shading_name(shading)));
      Image one = render_testscene(1, 42, sampler, shading),
            two = render_testscene(2, 42, sampler, shading),
            three = render_testscene(3, 42, sampler, shading);
      ASSERT_EQ(one.rgb.size(), two.rgb.size());
      EXPECT_EQ(std::memcmp(one.rgb.data(), two.rgb.data(), one.rgb.size() * sizeof(float)), 0);
      EXPECT_EQ(std::memcmp(one.rgb.data(), three.rgb.data(), one.rgb.size() * sizeof(float)), 0);
      Image other = render_testscene(2, 43, sampler, shading);
      std::size_t differ = 0;
      for (std::size_t i = 0; i < one.rgb.size(); ++i)
        differ += one.rgb[i] != other.rgb[i];
      EXPECT_GT(differ, one.rgb.size() / 2);  // another seed: most lit channels change
    }
}

// `lens 0 d` is the pinhole: the same image bit for bit, with either sampler (the lens draws
// no numbers of its own then). A real aperture changes the image.
TEST(PathTracer, ZeroApertureLensIsThePinholeImage) {
  for (Sampler sampler : kSamplers) {
    SCOPED_TRACE(sampler_name(sampler));
    auto p = load_scene_file(testing::source_path("scenes/testscene.scn"));
    ASSERT_TRUE(p.ok());
    p.scene.width = 32, p.scene.height = 24;
    PathSettings s;
    s.spp = 2;
    s.sampler = sampler;
    Image pinhole = render(p.scene, s);
    p.scene.lens = LensSpec{0, 1.5};
    Image zero = render(p.scene, s);
    EXPECT_EQ(std::memcmp(pinhole.rgb.data(), zero.rgb.data(), pinhole.rgb.size() * sizeof(float)),
              0);
    p.scene.lens = LensSpec{0.2, 1.5};
    Image blurred = render(p.scene, s);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < pinhole.rgb.size(); ++i)
      differ += pinhole.rgb[i] != blurred.rgb[i];
    EXPECT_GT(differ, pinhole.rgb.size() / 2);
  }
}

// The later course projects' materials (glass with absorption, mirror, glossy table) on the
// test scene: no NaN or inf sample, and light gets through the glass.
TEST(PathTracer, GlassAndMirrorRenderFinite) {
  auto p = load_scene_file(testing::source_path("scenes/testscene.scn"));
  ASSERT_TRUE(p.ok());
  Scene& scene = p.scene;
  scene.width = 40, scene.height = 30;
  for (Material& m : scene.materials) {
    if (m.alpha == 2000)
      m.kd = {0, 0, 0}, m.ks = {0.03f, 0.03f, 0.03f}, m.alpha = 10000, m.kt = {0.9f, 0.4f, 0.9f},
      m.ior = 1.25f;
    if (m.alpha == 200) m.ks = {0.255f, 0.24f, 0.09f};  // the glossy table
  }
  for (Shading shading : kShadings)
    for (Sampler sampler : kSamplers) {
      PathSettings s;
      s.spp = 4;
      s.sampler = sampler;
      s.shading = shading;
      PathStats stats;
      Image img = render(scene, s, &stats);
      EXPECT_EQ(stats.nonfinite_samples, 0u);
      for (float v : img.rgb)
        ASSERT_TRUE(std::isfinite(v) && v >= 0);
      EXPECT_GT(stats.bounce_rays, stats.camera_rays);
    }
}

// Float shading in lanes estimates the same image as the double Bsdf: the course scene's mean
// colour after 1024 samples per pixel (16 independent seeds × 64 spp at 32×24 pixels), per
// channel within 3 standard errors of the difference. The standard errors come from the
// spread of the 16 seeds' means; that they are below 0.5 % of the mean shows the test could
// see a bias of a few percent (a lobe's factor lost, a density off).
// The course scene, with its floor and a ball textured (whose Kd the lanes take per row), and
// under the sky (the environment's samples drawn a stage at a time).
class FloatShading : public ::testing::TestWithParam<const char*> {};

TEST_P(FloatShading, HasTheDoubleShadingsMean) {
  auto p = load_scene_file(testing::source_path(GetParam()));
  ASSERT_TRUE(p.ok());
  p.scene.width = 32, p.scene.height = 24;
  Bvh bvh = build_bvh_and_reorder(p.scene);
  Tracer tracer(p.scene, bvh, TracerBackend::kPacket);
  constexpr int kSeeds = 16;
  glm::dvec3 mean[2]{}, se[2]{};
  // Per pixel and channel: the sums of the seeds' values and of their squares.
  std::vector<double> pixel_s1[2], pixel_s2[2];
  for (Shading shading : kShadings) {
    int which = int(shading);
    pixel_s1[which].assign(std::size_t(p.scene.width) * p.scene.height * 3, 0.0);
    pixel_s2[which] = pixel_s1[which];
    glm::dvec3 s1(0, 0, 0), s2(0, 0, 0);
    for (int seed = 0; seed < kSeeds; ++seed) {
      PathSettings s;
      s.spp = 64;
      s.seed = uint64_t(100 + seed);
      s.shading = shading;
      PathStats stats;
      Image img = render_path(tracer, s, &stats);
      EXPECT_EQ(stats.nonfinite_samples, 0u);
      glm::dvec3 m(0, 0, 0);
      for (std::size_t i = 0; i < img.rgb.size(); i += 3)
        m += glm::dvec3(img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]);
      for (std::size_t i = 0; i < img.rgb.size(); ++i)
        pixel_s1[which][i] += img.rgb[i], pixel_s2[which][i] += double(img.rgb[i]) * img.rgb[i];
      m = m / double(img.rgb.size() / 3);
      s1 += m, s2 += m * m;
    }
    mean[which] = s1 / double(kSeeds);
    for (int k = 0; k < 3; ++k)
      se[which][k] = std::sqrt((s2[k] / kSeeds - mean[which][k] * mean[which][k]) / (kSeeds - 1));
  }
  for (int k = 0; k < 3; ++k) {
    double sigma = std::hypot(se[0][k], se[1][k]);
    std::printf("channel %d: double %.5f ± %.5f, float %.5f ± %.5f\n", k, mean[0][k], se[0][k],
                mean[1][k], se[1][k]);
    EXPECT_NEAR(mean[1][k], mean[0][k], 3 * sigma) << "channel " << k;
    EXPECT_LT(sigma, 0.005 * mean[0][k]) << "channel " << k;
  }
  // Per pixel: the two shadings' means over the seeds differ by z standard errors of their
  // difference (each from its 16 seeds' spread). Were the float shading biased in some pixels
  // only, they would stand out; with equal expectations, |z| > 4 has probability 0.0012 for
  // Student's t with 15 degrees of freedom (0.0012·2304 ≈ 3 expected; the same numbers drive
  // both shadings, so their difference is smaller still). Pixels with no spread at all (a
  // light seen directly, the black beyond the scene) must agree to float's precision.
  int far = 0, exact = 0;
  const std::size_t values = pixel_s1[0].size();
  for (std::size_t i = 0; i < values; ++i) {
    double m[2], v[2];
    for (int w = 0; w < 2; ++w) {
      m[w] = pixel_s1[w][i] / kSeeds;
      v[w] = std::max(0.0, pixel_s2[w][i] / kSeeds - m[w] * m[w]) / (kSeeds - 1);
    }
    const double se_diff = std::sqrt(v[0] + v[1]);
    if (se_diff <= 1e-7 * std::abs(m[0])) {
      ++exact;
      EXPECT_NEAR(m[1], m[0], 1e-5 * std::abs(m[0]) + 1e-30) << "value " << i;
      continue;
    }
    far += std::abs(m[1] - m[0]) > 4 * se_diff;
  }
  std::printf("%d of %zu pixel values beyond 4 standard errors, %d without spread\n", far, values,
              exact);
  EXPECT_LE(far, 10);
}

INSTANTIATE_TEST_SUITE_P(PathTracer, FloatShading,
                         ::testing::Values("scenes/testscene.scn", "scenes/testscene-textured.scn",
                                           "scenes/testscene-sky.scn", "scenes/csg.scn",
                                           "scenes/sdf.scn"));

}  // namespace
}  // namespace raylane
