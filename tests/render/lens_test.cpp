// The thin lens in the path tracer (docs/scene-language.md, "lens"): a small emitting sphere
// off the plane in focus images as a disc of the thin lens's circle of confusion; in the
// plane in focus it stays as sharp as the pinhole image.
#include <gtest/gtest.h>

#include <cmath>

#include "raylane/bvh/bvh.h"
#include "raylane/core/strings.h"
#include "raylane/render/path.h"
#include "raylane/scene/parser.h"

namespace raylane {
namespace {

// The camera at the origin looking down −Z (identity orientation), 64×64 pixels, ry = 0.25:
// a lateral offset of 1 at depth 1 spans (64/2)/0.25 = 128 pixels.
constexpr int kSize = 64;
constexpr double kRy = 0.25;
constexpr double kPixelsPerUnit = (kSize / 2) / kRy;

// A sphere of radius `rho` emitting 1, on the axis at depth `z`, nothing else in the scene.
Image render_sphere(double z, double rho, double lens_r, double focus, int spp) {
  std::string text = cat("screen ", kSize, " ", kSize, "\ncamera 0 0 0 ", kRy, "\nlens ", lens_r,
                         " ", focus, "\nlight 1 1 1\nsphere 0 0 ", -z, " ", rho, "\n");
  auto p = parse_scene(text, "lens.scn");
  EXPECT_TRUE(p.ok());
  Bvh bvh = build_bvh_and_reorder(p.scene);
  Tracer tracer(p.scene, bvh, TracerBackend::kPacket);
  PathSettings s;
  s.spp = spp;
  return render_path(tracer, s);
}

// The radius, in pixels, of the disc the image spreads over, from its flux and its plateau.
// A pixel's value is the chance that a ray through it (random point of the pixel, random point
// of the lens) hits the sphere. Summed over the image, that is the sphere's own image area A_s
// whatever the lens does; inside the blur disc (away from its rim by the sphere's image
// radius) it is A_s / A_c, A_c the disc's area. So A_c = flux / plateau: a measurement that
// uses every sample, where the disc's rim would use only a few noisy pixels.
double spread_radius(const Image& img, double plateau_radius) {
  double flux = 0, plateau = 0;
  int inside = 0;
  const double c = kSize / 2.0;
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x) {
      double v = img.at(x, y).x;
      flux += v;
      if (std::hypot(x + 0.5 - c, y + 0.5 - c) < plateau_radius) plateau += v, ++inside;
    }
  EXPECT_GT(inside, 8);
  plateau /= inside;
  return std::sqrt(flux / (M_PI * plateau));
}

TEST(ThinLens, AnOutOfFocusPointImagesAsTheCircleOfConfusion) {
  // Focus at depth 10, the sphere at depth 5. A ray from lens point r·(a, b) toward the focus
  // point of image direction D passes depth z at lateral r·(a, b)·(1 − z/d) + z·D, so the image
  // directions that see the axis point at depth z fill a disc of radius r·|1/d − 1/z|.
  const double r = 1.875, d = 10, z = 5;
  const double coc_pixels = r * std::abs(1 / d - 1 / z) * kPixelsPerUnit;  // 24
  const double rho = 4 * z / kPixelsPerUnit;  // the sphere's own image: 4 pixels of radius
  Image img = render_sphere(z, rho, r, d, 1024);
  double measured = spread_radius(img, coc_pixels - 4 - 2);
  std::printf("circle of confusion: measured %.3f px, thin lens %.3f px\n", measured, coc_pixels);
  EXPECT_NEAR(measured, coc_pixels, 1.0);
}

TEST(ThinLens, ThePlaneInFocusStaysSharp) {
  // In the plane in focus every lens point sees the sphere where the pinhole does: its image
  // is the sphere's own disc, ρ/z·(pixels per unit) = 4 pixels of radius, with a plateau of 1.
  const double d = 10, rho = 4 * d / kPixelsPerUnit;
  Image img = render_sphere(d, rho, 1.875, d, 64);
  double measured = spread_radius(img, 2);
  std::printf("in focus: measured %.3f px, pinhole 4 px\n", measured);
  EXPECT_NEAR(measured, 4.0, 0.5);
  // And nothing lands far outside it: the blur of the other test would put flux at 20 pixels.
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x) {
      if (std::hypot(x + 0.5 - kSize / 2.0, y + 0.5 - kSize / 2.0) <= 6) continue;
      ASSERT_EQ(img.at(x, y).x, 0.0f) << x << ", " << y;
    }
}

}  // namespace
}  // namespace raylane
