// The course's Monte Carlo path tracer (docs/design.md, "The course's rendering model"): next-event
// estimation toward emitting primitives, BSDF sampling, MIS with the power heuristic, Russian
// roulette. Each tile of 16×16 pixels traces its paths as wavefronts: all of a bounce's
// continuation and shadow rays go through the Tracer in one batch (so through the packet
// tracer), camera rays in 4×4 blocks. Passes of one sample per pixel run over the whole image
// (OpenMP over tiles); tile t of pass k draws from its own MT19937-64 stream seeded from
// (seed, t, k), or each pixel's decisions come from its own scrambled Sobol sequence, so an
// image is bit-identical for any number of threads.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

#include "raylane/core/enum_names.h"
#include "raylane/image/image.h"
#include "raylane/render/film/aov.h"
#include "raylane/render/film/region.h"
#include "raylane/render/film/tile_share.h"
#include "raylane/trace/tracer.h"

namespace raylane {

enum class Integrator {
  kBrdf,  // BSDF sampling only; emitters count where a path hits them
  kNee,   // light sampling only for direct light; emitters hit by bounces count nothing
  kMis,   // both, weighted by the power heuristic
};

inline constexpr EnumNames<Integrator, 3> kIntegratorNames{{"brdf", "nee", "mis"}};
inline std::optional<Integrator> integrator_from_name(std::string_view name) {
  return kIntegratorNames.from_name(name);
}
inline std::string_view integrator_name(Integrator integrator) {
  return kIntegratorNames.name(integrator);
}

// Where a path's random numbers come from (docs/design.md, "Samplers").
enum class Sampler {
  kMt19937,  // the course's MT19937-64: one stream per (seed, tile, pass), drawn in order
  kSobol,    // Owen-scrambled Sobol (render/samplers/sobol.h): a function of (seed, pixel, pass, decision)
};

inline constexpr EnumNames<Sampler, 2> kSamplerNames{{"mt19937", "sobol"}};
inline std::optional<Sampler> sampler_from_name(std::string_view name) {
  return kSamplerNames.from_name(name);
}
inline std::string_view sampler_name(Sampler sampler) {
  return kSamplerNames.name(sampler);
}

// Where the BSDF is sampled and evaluated (docs/design.md, "Shading in lanes").
enum class Shading {
  kDouble,  // the double Bsdf, one vertex at a time (films from before the choice: 0)
  kFloat,   // a wavefront's vertices at once in float SIMD lanes (render/materials/shade_lanes.h)
};

inline constexpr EnumNames<Shading, 2> kShadingNames{{"double", "float"}};
inline std::optional<Shading> shading_from_name(std::string_view name) {
  return kShadingNames.from_name(name);
}
inline std::string_view shading_name(Shading shading) {
  return kShadingNames.name(shading);
}

struct PathSettings {
  Integrator integrator = Integrator::kMis;
  Sampler sampler = Sampler::kSobol;
  Shading shading = Shading::kFloat;
  int spp = 16;
  uint64_t seed = 0;
  int max_depth = 64;        // bounces; Russian roulette ends nearly every path long before
  int rr_depth = 3;          // roulette from this bounce on, survival 0.8 (the course's rule)
  double time_limit = 0;     // seconds; 0 = none. Checked between passes.
  bool time_phases = false;  // fill PathStats::phases (a few clock reads per batch and vertex)
  AovSet aovs;               // accumulated in Film::aov_sum beside the colour (render/film/aov.h)
  // With the Sobol sampler, a thread's wavefront takes the next tile's camera rays whenever its
  // rays run low (src/render/wavefront/render_loop.h): the image is the same bit for bit
  // either way (tests/render/refill_test.cpp holds it to that); off, tile by tile.
  bool refill = true;
  TileShare share;  // the tiles this process renders (all of them by default)
  // Only the tiles that meet this pixel rectangle are rendered (render/film/region.h); the film
  // stays the image's size, zero elsewhere.
  std::optional<PixelRegion> region;
  const std::atomic<bool>* stop = nullptr;       // set → finish the pass in flight and return
  std::function<void(int passes_done)> on_pass;  // progress, called after each pass
  // Called after each pass but the last one taken, after on_pass (on every process of a job at
  // the same passes), with the thread-seconds each of this process's tiles took in that pass
  // (CPU time of the thread that rendered it, 0 for other tiles): returns the share for the
  // passes after it. A tile that changes hands must arrive with its sums in the film
  // (docs/cluster.md, "Balance"). Unset: `share` holds throughout and nothing is timed.
  std::function<TileShare(const std::vector<double>& tile_seconds)> reshare;
};

// Thread-seconds spent in each phase of the render loop, summed over the threads (`--stats`).
struct PathPhases {
  double camera = 0;  // making camera rays
  // Tracing: a step's time is shared between its camera rays and the rest (bounce and shadow
  // rays) by their counts.
  double trace_camera = 0;
  double trace_rest = 0;
  double shade = 0;   // emission, absorption, BSDF sampling and evaluation, roulette
  double lights = 0;  // light sampling (inside shading; not counted in `shade`)
  double film = 0;    // adding the finished tiles' samples to the film
  double total() const { return camera + trace_camera + trace_rest + shade + lights + film; }
  void add(const PathPhases& o);
};

struct PathStats {
  PathPhases phases;  // with PathSettings::time_phases
  uint64_t camera_rays = 0, bounce_rays = 0, shadow_rays = 0;
  uint64_t nonfinite_samples = 0;  // samples dropped for NaN/inf radiance (should stay 0)
  // Wavefront steps (one trace of a thread's rays and shadow rays, and the shading after it):
  // rays() / steps is how full the wavefronts ran.
  uint64_t steps = 0;
  int passes = 0;  // samples per pixel actually taken
  uint64_t rays() const { return camera_rays + bounce_rays + shadow_rays; }
};

struct Film;

// Renders tracer.scene(); the image is the mean over the passes taken (top row first). With
// a `film`, the sums accumulate there (for checkpoints, which on_pass may save) and a film that
// already holds passes is continued from its next pass up to settings.spp — the same image
// an uninterrupted run gives. Contract: a non-empty film matches the scene's size and
// film_fingerprint(scene, settings); it sums the AOVs it was started with (settings.aovs
// chooses them for an empty film).
Image render_path(const Tracer& tracer, const PathSettings& settings, PathStats* stats = nullptr,
                  Film* film = nullptr);

}  // namespace raylane
