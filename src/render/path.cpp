#include "raylane/render/path.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include <omp.h>

#include "raylane/render/camera/camera.h"
#include "raylane/render/film/film.h"
#include "render/wavefront/render_loop.h"

namespace raylane {

using namespace path_detail;

namespace {

void add_stats(PathStats& into, const PathStats& s) {
  into.phases.add(s.phases);
  into.camera_rays += s.camera_rays;
  into.bounce_rays += s.bounce_rays;
  into.shadow_rays += s.shadow_rays;
  into.nonfinite_samples += s.nonfinite_samples;
  into.steps += s.steps;
}

}  // namespace

void PathPhases::add(const PathPhases& o) {
  camera += o.camera, trace_camera += o.trace_camera, trace_rest += o.trace_rest;
  shade += o.shade, lights += o.lights, film += o.film;
}

Image render_path(const Tracer& tracer, const PathSettings& settings, PathStats* stats,
                  Film* film) {
  const Scene& scene = tracer.scene();
  Camera cam = Camera::from_scene(scene);
  LightSampler lights(scene);
  LaneMaterials lane_materials(scene.materials);
  const LaneShading lanes{lane_materials, tracer.isa(), detail::render_lanes(tracer.isa())};
  const std::ptrdiff_t tiles = std::ptrdiff_t((cam.width + kTile - 1) / kTile) *
                               std::ptrdiff_t((cam.height + kTile - 1) / kTile);
  Film own;
  Film& f = film ? *film : own;
  if (f.sum.empty()) {
    f.aovs = settings.aovs;
    f.region = settings.region;
    f.clear(cam.width, cam.height);
  }
  PathStats total;
  total.passes = f.passes;
  auto start = std::chrono::steady_clock::now();
  // Each thread's wavefront lives across passes: regrown every pass, it cost 2-thread scaling.
  std::vector<Wavefront> per_thread(static_cast<std::size_t>(omp_get_max_threads()));
  TileShare share = settings.share;
  std::vector<double> tile_seconds(settings.reshare ? std::size_t(tiles) : 0);
  for (int pass = f.passes; pass < settings.spp; ++pass) {
    TileClaims claims(cam, share, settings);
#pragma omp parallel
    {
      // The team may be larger than omp_get_max_threads() said before it (seen under clang's
      // libomp with ASan: buffers for one thread, and a thread 1 in the team); the single's
      // barrier comes before any thread takes its buffers.
#pragma omp single
      if (per_thread.size() < std::size_t(omp_get_num_threads()))
        per_thread.resize(std::size_t(omp_get_num_threads()));
      ThreadContext ctx{
          per_thread[std::size_t(omp_get_thread_num())],   tracer, lights, settings,      lanes,
          Rng::for_tile(settings.seed, 0, uint64_t(pass)), {},     0,      uint32_t(pass)};
      render_claimed_tiles(ctx, cam, claims, f, tile_seconds);
#pragma omp critical
      add_stats(total, ctx.stats);
    }
    total.passes = f.passes = pass + 1;
    if (settings.on_pass) settings.on_pass(total.passes);
    if (settings.stop && settings.stop->load()) break;
    double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (settings.time_limit > 0 && elapsed >= settings.time_limit) break;
    if (settings.reshare && pass + 1 < settings.spp) {
      share = settings.reshare(tile_seconds);
      std::fill(tile_seconds.begin(), tile_seconds.end(), 0.0);
    }
  }
  if (stats) *stats = total;
  return f.image();
}

}  // namespace raylane