// Motion blur against static renders (docs/motion-blur.md): a moving sphere's image is the time
// average of the images of the sphere where it is at each time, and an mbsphere whose ends are
// equal is the sphere. Compared in expectation: strips of pixels across the motion, each strip's
// mean difference against the standard error its pixels' differences give.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "raylane/bvh/bvh.h"
#include "raylane/core/strings.h"
#include "raylane/render/path.h"
#include "raylane/render/raycast.h"
#include "raylane/scene/parser.h"

namespace raylane {
namespace {

// A lit wall behind a diffuse, slightly glossy ball, seen from the front (z up); `ball` is the
// ball's line.
std::string ball_scene(const std::string& ball) {
  return "screen 64 48\ncamera 0 -6 0.5 0.4 x 90\nambient 0 0 0\n"
         "light 6 6 6\nsphere -2 -3 4 1\n"
         "brdf 0.6 0.6 0.6 0 0 0 10\nbox -10 2 -10 20 1 20\nbox -10 -10 -1.5 20 20 0.5\n"
         "brdf 0.8 0.3 0.2 0.2 0.2 0.2 50\n" +
         ball + "\n";
}

Image render(const std::string& text, const PathSettings& settings) {
  auto p = parse_scene(text, "motion.scn");
  EXPECT_TRUE(p.ok());
  Bvh bvh = build_bvh_and_reorder(p.scene);
  Tracer tracer(p.scene, bvh, TracerBackend::kPacket);
  return render_path(tracer, settings);
}

// The strips of `columns` pixel columns: for each strip and channel, the mean of the pixels'
// differences a − b in units of its standard error (the spread of those differences: the pixels
// are independent estimates); the largest |z| and the largest standard error relative to the
// strip's mean of b.
struct StripComparison {
  double max_z = 0, max_relative_sigma = 0;
  int strips = 0;
};
StripComparison compare_strips(const Image& a, const Image& b, uint32_t columns) {
  StripComparison out;
  for (uint32_t x0 = 0; x0 < a.width; x0 += columns) {
    ++out.strips;
    for (int c = 0; c < 3; ++c) {
      double s = 0, s2 = 0, sb = 0;
      std::size_t n = 0;
      for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = x0; x < std::min(a.width, x0 + columns); ++x, ++n) {
          std::size_t i = (std::size_t(y) * a.width + x) * 3 + std::size_t(c);
          double d = double(a.rgb[i]) - b.rgb[i];
          s += d, s2 += d * d, sb += b.rgb[i];
        }
      double mean = s / double(n);
      double sigma = std::sqrt(std::max(0.0, s2 / double(n) - mean * mean) / double(n - 1));
      out.max_z = std::max(out.max_z, sigma > 0 ? std::abs(mean) / sigma : mean == 0 ? 0 : 1e9);
      out.max_relative_sigma = std::max(out.max_relative_sigma, sigma / (sb / double(n)));
    }
  }
  return out;
}

// 16 strips × 3 channels = 48 comparisons; |z| ≤ 4 for all of them fails by chance with
// probability 1 − (1 − 6.3e-5)^48 ≈ 0.3 %.
constexpr double kMaxZ = 4.0;

// The same sphere as `sphere` and as an `mbsphere` that does not move, under MT19937 (the moving
// scene draws one more number per path, so the two images' noise is independent).
TEST(MotionBlur, AnMbsphereWithEqualEndsRendersAsTheSphere) {
  PathSettings s;
  s.sampler = Sampler::kMt19937;
  s.spp = 64;
  Image still = render(ball_scene("sphere 0.3 0 0.2 0.9"), s);
  Image moving = render(ball_scene("mbsphere 0.3 0 0.2 0.3 0 0.2 0.9"), s);
  StripComparison c = compare_strips(moving, still, 4);
  std::printf("equal ends: %d strips, max |z| %.3f, max sigma/mean %.4f\n", c.strips, c.max_z,
              c.max_relative_sigma);
  EXPECT_LE(c.max_z, kMaxZ);
  EXPECT_LT(c.max_relative_sigma, 0.05);  // power: a 20 % error is far outside 4σ
}

// The ball moves 2.4 units across the picture (about 26 pixels). The reference is the mean of
// K static renders with the ball at the midpoints of K equal time strata: each strip's mean,
// as a function of the ball's place, is smooth (the ball's projected area in the strip), so
// the midpoint rule's error at K = 24 is far below the noise.
TEST(MotionBlur, AMovingSpheresImageIsTheAverageOfStaticRendersAtStratifiedTimes) {
  PathSettings s;
  s.spp = 64;
  const double x0 = -1.2, x1 = 1.2;
  Image moving = render(ball_scene(cat("mbsphere ", x0, " 0 0.2 ", x1, " 0 0.2 0.9")), s);
  constexpr int K = 24;
  Image average = moving;
  std::fill(average.rgb.begin(), average.rgb.end(), 0.0f);
  std::vector<double> sum(average.rgb.size(), 0.0);
  for (int k = 0; k < K; ++k) {
    PathSettings sk = s;
    sk.seed = uint64_t(k + 1);  // independent noise in each static render
    sk.spp = 16;
    const double t = (k + 0.5) / K, x = x0 + t * (x1 - x0);
    Image still = render(ball_scene(cat("sphere ", x, " 0 0.2 0.9")), sk);
    for (std::size_t i = 0; i < sum.size(); ++i)
      sum[i] += still.rgb[i];
  }
  for (std::size_t i = 0; i < sum.size(); ++i)
    average.rgb[i] = float(sum[i] / K);
  StripComparison c = compare_strips(moving, average, 4);
  std::printf("moving vs %d static renders: %d strips, max |z| %.3f, max sigma/mean %.4f\n", K,
              c.strips, c.max_z, c.max_relative_sigma);
  EXPECT_LE(c.max_z, kMaxZ);
  EXPECT_LT(c.max_relative_sigma, 0.05);
  // And the blur is there: the ball at mid-shutter alone is far from the moving image.
  Image middle = render(ball_scene("sphere 0 0 0.2 0.9"), s);
  EXPECT_GT(compare_strips(moving, middle, 4).max_z, 10.0);
}

// An emitting ball sweeping low over the floor (4 units, 0.1 above it at its lowest) beside the
// still light. Light sampling must find it where it is at each path's time: with MIS and with
// next-event estimation alone, in the float lanes and in double shading, the image is in
// expectation the one BSDF sampling alone gives (which finds the light wherever the path's rays
// meet it). 4 renders × 48 comparisons: |z| ≤ 4.5 for all fails by chance with probability
// 1 − (1 − 6.8e-6)^192 ≈ 0.13 %. The still scene's wall and floor are lit by the moving ball
// very differently at each time, so a sample at another time (mid-shutter) is far outside.
TEST(MotionBlur, AMovingLightIsLightSampledAtThePathsTime) {
  const std::string scene = ball_scene("sphere 1.3 0.5 0 0.5") +
                            "light 30 30 30\nmbsphere -2 -1.5 -0.6 2 -1.5 -0.6 0.3\n";
  PathSettings bsdf_only;
  bsdf_only.integrator = Integrator::kBrdf;
  bsdf_only.spp = 4096;
  bsdf_only.seed = 1;
  const Image reference = render(scene, bsdf_only);
  for (Shading shading : {Shading::kFloat, Shading::kDouble})
    for (Integrator integrator : {Integrator::kMis, Integrator::kNee}) {
      PathSettings s;
      s.integrator = integrator;
      s.shading = shading;
      s.spp = 256;
      s.seed = 2;  // independent of the reference's noise
      StripComparison c = compare_strips(render(scene, s), reference, 4);
      std::printf(
          "moving light, %s, %s shading, vs brdf: %d strips, max |z| %.3f, max "
          "sigma/mean %.4f\n",
          std::string(integrator_name(integrator)).c_str(),
          std::string(shading_name(shading)).c_str(), c.strips, c.max_z, c.max_relative_sigma);
      EXPECT_LE(c.max_z, 4.5);
      EXPECT_LT(c.max_relative_sigma, 0.05);
    }
}

// The ray-casting views show the shutter's middle (docs/motion-blur.md): a ball moving from
// x = −1.25 to 1.25 is, at time 0.5, the ball at x = 0 (c0 + 0.5·m is exactly 0 in float), so
// each view's image is the still ball's: bit for bit for the references and for the packet
// tracer's depths; the packet tracer's still ball takes its surface from the double lanes and
// the moving one from surface_ref (the same point and normal up to double rounding), so there
// the float shading normal may differ by an ulp per component (2^-24), which moves the normal
// view's values by a few float ulps and a lit cosine by a few 2^-24: 2^-20 of the image's
// largest value bounds both.
TEST(MotionBlur, RayCastingViewsShowTheMiddleOfTheShutter) {
  for (TracerBackend kind : {TracerBackend::kPacket, TracerBackend::kBvh}) {
    for (RaycastMode mode : {RaycastMode::kDepth, RaycastMode::kNormal, RaycastMode::kLit}) {
      auto view = [&](const std::string& ball) {
        auto p = parse_scene(ball_scene(ball), "motion.scn");
        EXPECT_TRUE(p.ok());
        Bvh bvh = build_bvh_and_reorder(p.scene);
        return render_raycast(Tracer(p.scene, bvh, kind), mode);
      };
      Image moving = view("mbsphere -1.25 0 0.2 1.25 0 0.2 0.9");
      Image still = view("sphere 0 0 0.2 0.9");
      SCOPED_TRACE(cat(raycast_mode_name(mode), " ", tracer_backend_name(kind)));
      if (kind != TracerBackend::kPacket || mode == RaycastMode::kDepth) {
        EXPECT_EQ(moving.rgb, still.rgb);
      } else {
        ASSERT_EQ(moving.rgb.size(), still.rgb.size());
        const float scale = *std::max_element(still.rgb.begin(), still.rgb.end());
        for (std::size_t i = 0; i < moving.rgb.size(); ++i)
          ASSERT_NEAR(moving.rgb[i], still.rgb[i], 0x1p-20 * scale) << i;
      }
      Image start = view("sphere -1.25 0 0.2 0.9");
      EXPECT_NE(moving.rgb, start.rgb);
    }
  }
}

}  // namespace
}  // namespace raylane
