// Writes the images of the example scenes, so that nothing in scenes/ is downloaded:
//   make_maps checker OUT.png   a 256×256 checkerboard texture (8×8 squares, sRGB), with a red
//                               square in the top-left corner and a blue one in the bottom-right
//                               so that orientation mistakes show
//   make_maps sky OUT.hdr       a 512×256 equirectangular sky (docs/scene-language.md,
//                               "Equirectangular environment mapping"): a blue gradient above the
//                               horizon, a dim ground below and a sun 2° across
#include <cmath>
#include <cstdio>
#include <string>

#include "raylane/core/vec_math.h"
#include "raylane/core/warps.h"
#include "raylane/image/write_image.h"

namespace {

using glm::dvec3;
using glm::vec3;
using raylane::Image;
using raylane::kPi;

Image checker() {
  constexpr uint32_t kSize = 256, kSquare = 32;
  Image img(kSize, kSize);
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      uint32_t cx = x / kSquare, cy = y / kSquare;
      glm::vec3 c =
          (cx + cy) % 2 == 0 ? glm::vec3(0.85f, 0.82f, 0.75f) : glm::vec3(0.12f, 0.13f, 0.16f);
      if (cx == 0 && cy == 0) c = {0.8f, 0.1f, 0.1f};  // top-left: red
      if (cx == 7 && cy == 7) c = {0.1f, 0.2f, 0.8f};  // bottom-right: blue
      img.set(x, y, c);
    }
  return img;
}

// The sun: elevation 35°, azimuth 60° from +X towards +Y, angular radius 1°.
glm::dvec3 sun_direction() {
  double elev = 35 * kPi / 180, az = 60 * kPi / 180;
  return {std::cos(elev) * std::cos(az), std::cos(elev) * std::sin(az), std::sin(elev)};
}

glm::vec3 sky_radiance(const glm::dvec3& d) {
  const double cos_sun = std::cos(1.0 * kPi / 180);
  if (dot(d, sun_direction()) >= cos_sun) return {3000.0f, 2800.0f, 2500.0f};
  if (d.z < 0) return {0.18f, 0.16f, 0.14f};  // ground
  // Zenith blue fading to a pale horizon, brighter towards the sun.
  double h = std::pow(1 - d.z, 3);
  double glow = std::pow(std::max(0.0, dot(d, sun_direction())), 8) * 0.8;
  glm::dvec3 c = (1 - h) * glm::dvec3(0.25, 0.45, 1.0) + h * glm::dvec3(0.9, 0.95, 1.0) +
                 glow * glm::dvec3(1, 0.9, 0.7);
  return glm::vec3(c * 1.2);
}

Image sky() {
  constexpr uint32_t kW = 512, kH = 256, kSub = 4;  // 4×4 sub-samples per pixel: a smooth sun
  Image img(kW, kH);
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      glm::dvec3 sum(0, 0, 0);
      for (uint32_t sy = 0; sy < kSub; ++sy)
        for (uint32_t sx = 0; sx < kSub; ++sx) {
          double u = (x + (sx + 0.5) / kSub) / kW, v = (y + (sy + 0.5) / kSub) / kH;
          double phi = 2 * kPi * u, theta = kPi * v;
          glm::dvec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                       std::cos(theta));
          sum += glm::dvec3(sky_radiance(d));
        }
      img.set(x, y, glm::vec3(sum / double(kSub * kSub)));
    }
  return img;
}

}  // namespace

int main(int argc, char** argv) {
  std::string what = argc == 3 ? argv[1] : "";
  if (what != "checker" && what != "sky") {
    std::fprintf(stderr, "usage: make_maps checker OUT.png | make_maps sky OUT.hdr\n");
    return 2;
  }
  Image img = what == "checker" ? checker() : sky();
  if (auto s = raylane::write_image(argv[2], img); !s) {
    std::fprintf(stderr, "make_maps: %s\n", s.error().c_str());
    return 1;
  }
  std::printf("%s\n", argv[2]);
  return 0;
}
