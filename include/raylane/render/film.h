// The path tracer's film: per-pixel sums of radiance over the passes taken, so a render can
// be saved (`--checkpoint`) and continued later (`--resume`) to exactly the image an
// uninterrupted run gives: pass k of tile t always draws from the stream (seed, t, k), and the
// sums are added in the same order (issue 6, "Nothing lost").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/image/image.h"
#include "raylane/render/path.h"

namespace raylane {

struct Film {
  uint32_t width = 0, height = 0;
  int passes = 0;            // samples per pixel summed so far
  std::vector<double> sum;   // 3 per pixel, top row first
  uint64_t fingerprint = 0;  // of the scene and the settings whose samples these are

  Image image() const;  // the mean over the passes (black before the first)
};

// Identifies what a film's samples depend on: the scene (tables, materials, camera, screen)
// and the settings that shape each sample (seed, integrator, depth, roulette) — not spp or
// time, which only say how many passes to take.
uint64_t film_fingerprint(const Scene& scene, const PathSettings& settings);

// `.film` files: magic "RLFILM1\0", width, height, passes, 0 (uint32 each), fingerprint
// (uint64), then width·height·3 float64 sums; little endian. Written atomically.
Status save_film(const std::string& path, const Film& film);
Result<Film> load_film(const std::string& path);

}  // namespace raylane
