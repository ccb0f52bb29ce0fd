// The path tracer's film: per-pixel sums of radiance over the passes taken, so a render can
// be saved (`--checkpoint`) and continued later (`--resume`) to exactly the image an
// uninterrupted run gives: pass k of tile t always draws from the stream (seed, t, k), and the
// sums are added in the same order (docs/design.md, "Determinism").
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/image/image.h"
#include "raylane/render/path.h"

namespace raylane {

// Where a film's samples come from, part by part, so that a --resume that does not match can
// say what differs. A film of the first format (RLFILM1) knows only its fingerprint: its
// `known` is false.
struct FilmOrigin {
  bool known = false;
  uint64_t scene = 0;  // scene_fingerprint
  uint64_t seed = 0;
  int32_t integrator = 0, max_depth = 0, rr_depth = 0;
  int32_t sampler = 0;  // Sampler; 0 (MT19937) in films written before there was a choice
  int32_t shading = 0;  // Shading; 0 (double) in films written before there was a choice
};

// A film holds the pixels it sums and no others: a --region's film, its AOVs and the images
// made from it are the region's size, whatever the screen's (a 4x4 region of a 16384² screen
// takes bytes, not gigabytes). Pixels are named by their index in the whole image (y·width +
// x, top row first), as the renderer numbers them; slot() says where the sums keep one.
struct Film {
  uint32_t width = 0, height = 0;  // the whole image's
  int passes = 0;                  // samples per pixel summed so far
  std::vector<double> sum;         // 3 per stored pixel, top row first
  uint64_t fingerprint = 0;        // of the scene and the settings whose samples these are
  FilmOrigin origin;
  AovSet aovs;                        // which AOVs the film sums (render/film/aov.h)
  std::vector<double> aov_sum;        // aovs.channels() per stored pixel, top row first
  std::optional<PixelRegion> region;  // --region: the pixels it sums; none: the whole image

  static constexpr std::size_t kNotStored = kNotInRegion;

  // The rectangle of stored pixels: the region, or the whole image.
  PixelRegion window() const;
  std::size_t stored_pixels() const;
  // Where the sums keep image pixel `pixel` (y·width + x): its stored index, or kNotStored
  // for a pixel outside the region (rendered with its tile, then dropped).
  std::size_t slot(std::size_t pixel) const;
  // Zeroed sums, colour and AOVs, for the stored pixels of a width × height image.
  void clear(uint32_t image_width, uint32_t image_height);

  Image image() const;  // the stored pixels' mean over the passes (black before the first)
  // The mean of one AOV the film sums; depth in all three channels.
  Image aov_image(Aov aov) const;
  // The whole width × height image with the stored pixels in their place, black elsewhere:
  // what a viewer of the whole screen shows.
  Image screen_image() const;
};

// Zeroes the film's sums (colour and AOVs) outside the share's tiles: what a process of several
// keeps of a film it resumes, so that the processes' films add up to the whole exactly.
void keep_share(Film& film, const TileShare& share);

// Identifies what a film's samples depend on: the scene (tables, materials, camera, screen)
// and the settings that shape each sample (seed, integrator, depth, roulette) — not spp or
// time, which only say how many passes to take.
uint64_t film_fingerprint(const Scene& scene, const PathSettings& settings);
uint64_t scene_fingerprint(const Scene& scene);  // the scene's part alone
FilmOrigin film_origin(const Scene& scene, const PathSettings& settings);
FilmOrigin film_origin(uint64_t scene_print, const PathSettings& settings);
// Sets the film's fingerprint and origin for these settings, in one pass over the scene. Only
// a film that is saved needs them (render_path leaves them alone): a render or a viewer frame
// without --checkpoint never pays that pass.
void identify_film(Film& film, const Scene& scene, const PathSettings& settings);

// What differs between a film's origin and this run's, in the user's terms ("the scene",
// "--seed 3 (this run: 0)", ...), joined by "; "; empty if nothing (or if the film does not
// know its origin).
std::string origin_difference(const FilmOrigin& film, const FilmOrigin& run);

// `.film` files: magic "RLFILM2\0", width, height, passes, integrator (uint32 each),
// fingerprint, scene fingerprint, seed (uint64 each), max depth, roulette depth, sampler,
// shading (uint32 each; the sampler's and the shading's words were 0 before there was a
// choice), then
// width·height·3 float64 sums; little endian. A film with AOVs ends in "AOV1", the set's bits
// (uint32) and width·height·channels float64 AOV sums. A film of a --region is "RLFILM3\0":
// the same header, then the region's x0, y0, x1, y1 (uint32 each), and sums of the region's
// pixels alone. Written atomically. Still read: the first format ("RLFILM1\0", a 32-byte
// header: width, height, passes, 0, fingerprint), and region films of the second, whose sums
// covered the whole image, followed by "RGN1" and the corners (cut to the region as read).
Status save_film(const std::string& path, const Film& film);
Result<Film> load_film(const std::string& path);

}  // namespace raylane
