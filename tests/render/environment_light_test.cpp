// The environment as a light of the path tracer (render/lights/lights.h, render/path.h): furnaces
// with analytic answers, the orientation moving the light, and the `environment` command's rules.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "raylane/bvh/bvh.h"
#include "raylane/core/strings.h"
#include "raylane/image/pfm.h"
#include "raylane/render/lights/environment.h"
#include "raylane/render/path.h"
#include "raylane/scene/parser.h"
#include "scene/scene_test_util.h"
#include "support/estimate.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::errors;
using testing::warnings;

std::string write_pfm(const std::string& name, const Image& img) {
  std::string path = testing::temp_dir() + "/" + name;
  std::ofstream(path, std::ios::binary) << encode_pfm(img);
  return path;
}

Image constant_map(float value) {
  Image img(8, 4);
  for (float& v : img.rgb)
    v = value;
  return img;
}

// 64×32 map, black but for a cap of bright rows around the top (+Z): rows [0, cap_rows).
Image cap_map(uint32_t cap_rows, float value) {
  Image img(64, 32);
  for (uint32_t y = 0; y < cap_rows; ++y)
    for (uint32_t x = 0; x < 64; ++x)
      img.set(x, y, {value, value, value});
  return img;
}

ParsedScene parse_ok(const std::string& text) {
  auto p = parse_scene(text, testing::temp_dir() + "/env.scn");
  EXPECT_TRUE(p.ok()) << ::testing::PrintToString(errors(p));
  return p;
}

testing::Estimate render_pixels(ParsedScene& p, Integrator integrator, Shading shading, int spp) {
  Bvh bvh = build_bvh_and_reorder(p.scene);
  Tracer tracer(p.scene, bvh, TracerBackend::kPacket);
  PathSettings s;
  s.integrator = integrator;
  s.shading = shading;
  s.sampler = Sampler::kSobol;
  s.spp = spp;
  s.seed = 3;
  PathStats stats;
  Image img = render_path(tracer, s, &stats);
  EXPECT_EQ(stats.nonfinite_samples, 0u);
  std::size_t i = 0;
  std::size_t n = std::size_t(img.width) * img.height;
  return testing::estimate(int(n), [&] { return double(img.rgb[3 * i++]); });
}

constexpr Integrator kIntegrators[] = {Integrator::kBrdf, Integrator::kNee, Integrator::kMis};
constexpr Shading kShadings[] = {Shading::kDouble, Shading::kFloat};

// A diffuse sphere (ρ = 0.5) in a constant environment L = 0.8: convex, so every reflected ray
// escapes and the sphere shows ρ·L = 0.4 everywhere; looking away, the background is L itself.
TEST(EnvironmentLight, FurnaceSphereShowsAlbedoTimesTheEnvironment) {
  std::string map = write_pfm("const.pfm", constant_map(0.8f));
  for (Shading shading : kShadings)
    for (Integrator integrator : kIntegrators) {
      auto p = parse_ok("screen 16 16\ncamera 0 0 3 0.2\nenvironment \"" + map +
                        "\" 1\nbrdf 0.5 0.5 0.5 0 0 0 1\nsphere 0 0 0 1\n");
      testing::Estimate e = render_pixels(p, integrator, shading, 32);
      std::string what = cat(integrator_name(integrator), "/", shading_name(shading));
      std::printf("environment furnace %s: %.5f ± %.5f (expected 0.4)\n", what.c_str(), e.mean,
                  e.sigma);
      EXPECT_NEAR(e.mean, 0.4, 4 * e.sigma + 1e-6) << what;
      EXPECT_LT(e.sigma, 0.004) << what;
    }
  auto away = parse_ok("screen 8 8\ncamera 0 0 3 0.2 x 180\nenvironment \"" + map +
                       "\" 2\nbrdf 0.5 0.5 0.5 0 0 0 1\nsphere 0 0 0 1\n");
  testing::Estimate bg = render_pixels(away, Integrator::kMis, Shading::kFloat, 4);
  EXPECT_NEAR(bg.mean, 1.6, 1e-6);  // s·L, exactly: camera rays see it with weight 1
  EXPECT_EQ(bg.sigma, 0);
}

// ρ/π ∫ over the upper hemisphere of the map's radiance × cos θ: the radiance an upward
// diffuse plane leaves, by midpoint quadrature of the bilinear map (fine enough for 1e-4).
double plane_radiance(const EnvironmentMap& env, double rho) {
  const int nt = 720, np = 1440;
  double sum = 0;
  for (int i = 0; i < nt; ++i) {
    double theta = (i + 0.5) / nt * kPi / 2;
    for (int j = 0; j < np; ++j) {
      double phi = (j + 0.5) / np * 2 * kPi;
      glm::dvec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta));
      sum += env.radiance(d).x * std::cos(theta) * std::sin(theta);
    }
  }
  return rho / kPi * sum * (kPi / 2 / nt) * (2 * kPi / np);
}

// An upward plane (ρ = 0.5) under a bright cap of sky (rows above θ = 22.5°), seen from above:
// radiance ρ/π·∫ L cos θ dω. Turning the map by the orientation moves the cap: "x 90" puts it
// on the horizon (less light), "x 180" under the plane (none).
TEST(EnvironmentLight, UpwardPlaneUnderACapMatchesTheIrradianceIntegral) {
  Image cap = cap_map(4, 20.0f);
  std::string map = write_pfm("cap.pfm", cap);
  struct Case {
    const char* orientation;
    glm::dmat3 r{1.0};
  };
  const Case cases[] = {{"", glm::dmat3(1.0)},
                        {"x 90", rotation_axis_angle({1, 0, 0}, 90)},
                        {"x 180", rotation_axis_angle({1, 0, 0}, 180)}};
  for (const Case& c : cases) {
    double expected = plane_radiance(EnvironmentMap(cap, 1, c.r), 0.5);
    for (Integrator integrator : kIntegrators) {
      auto p =
          parse_ok(std::string("screen 16 16\ncamera 0 0 2 0.05\nenvironment \"") + map + "\" 1 " +
                   c.orientation + "\nbrdf 0.5 0.5 0.5 0 0 0 1\nbox -50 -50 -1 100 100 1\n");
      // BSDF sampling alone finds a cap on the horizon rarely: it needs more samples.
      int spp = integrator == Integrator::kBrdf ? 256 : 64;
      testing::Estimate e = render_pixels(p, integrator, Shading::kFloat, spp);
      std::printf("cap '%s' %s: %.5f ± %.5f (expected %.5f)\n", c.orientation,
                  integrator_name(integrator).data(), e.mean, e.sigma, expected);
      EXPECT_NEAR(e.mean, expected, 4 * e.sigma + 1e-9) << c.orientation;
      if (expected > 0) {
        EXPECT_LT(e.sigma, 0.05 * expected) << c.orientation;
      }
    }
    if (std::string(c.orientation) == "x 180") {
      EXPECT_EQ(expected, 0.0);  // the cap under the plane: nothing reaches it
    }
  }
}

TEST(EnvironmentCommand, NeedsAFileAPositiveScaleAndTheLastOneWins) {
  std::string map = write_pfm("const.pfm", constant_map(1.0f));
  auto missing = testing::parse(std::string(testing::kCameraLine) + "environment sky.hdr 1\n");
  ASSERT_EQ(errors(missing).size(), 1u);
  EXPECT_THAT(errors(missing)[0],
              ::testing::HasSubstr("t.scn:2:13: environment 'sky.hdr' not found"));
  auto zero = testing::parse(std::string(testing::kCameraLine) + "environment \"" + map + "\" 0\n");
  ASSERT_EQ(errors(zero).size(), 1u);
  EXPECT_THAT(errors(zero)[0], ::testing::HasSubstr("environment scale must be > 0"));
  auto no_scale =
      testing::parse(std::string(testing::kCameraLine) + "environment \"" + map + "\"\n");
  ASSERT_EQ(errors(no_scale).size(), 1u);
  auto bad_turn =
      testing::parse(std::string(testing::kCameraLine) + "environment \"" + map + "\" 1 w 3\n");
  ASSERT_EQ(errors(bad_turn).size(), 1u);
  auto twice = testing::parse(std::string(testing::kCameraLine) + "screen 4 4\nenvironment \"" +
                              map + "\" 1\nenvironment \"" + map + "\" 3 z 90\n");
  ASSERT_TRUE(twice.ok());
  ASSERT_EQ(warnings(twice).size(), 1u);
  EXPECT_THAT(warnings(twice)[0],
              ::testing::HasSubstr("t.scn:4:1: warning: environment given again"));
  ASSERT_TRUE(twice.scene.environment);
  EXPECT_EQ(twice.scene.environment->scale, 3);
}

}  // namespace
}  // namespace raylane
