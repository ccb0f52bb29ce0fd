#include "raylane/render/path.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <utility>

#include <omp.h>

#include "raylane/render/camera.h"
#include "raylane/render/film.h"
#include "render/wavefront/stages.h"

namespace raylane {

using namespace path_detail;

namespace {

// One sample for every pixel of a tile (its camera rays already in `rays`), depth by depth:
// each depth traces the live paths' rays and the shadow rays of the vertices before, then
// runs the stages of render/wavefront/stages.h, which fill the next depth's queues.
void render_tile(TileContext& ctx, Film& f) {
  Wavefront& w = ctx.wave;
  w.shadows.clear();
  ctx.stats.camera_rays += w.paths.size();
  PathPhases& phases = ctx.stats.phases;
  const double lights_at_start = phases.lights, shade_at_start = phases.shade;
  PhaseClock clock(ctx.settings.time_phases);
  for (int depth = 0; !w.rays.empty() || !w.shadows.empty(); ++depth) {
    clock.lap(phases.shade);
    // Surfaces for every hit only where they are all read: the double shading's vertices, the
    // AOVs of the camera hits. Otherwise prim and t alone, and the surfaces of the vertices that
    // need one follow: the lanes' into their columns (Tracer::surfaces), the rest one by one.
    const bool all_surfaces = ctx.settings.shading == Shading::kDouble ||
                              (depth == 0 && !f.aovs.empty()) ||
                              ctx.tracer.backend() != TracerBackend::kPacket;
    stamp_times(ctx);
    ctx.tracer.closest(w.rays.rays, w.hits, all_surfaces ? w.rays.size() : 0, w.scratch);
    w.hits_have_surfaces = all_surfaces;
    // Shadow rays, aimed at their light: it is seen when nothing else lies before it.
    ctx.tracer.occluded(w.shadows.rays, w.blocked, w.scratch);
    clock.lap(depth == 0 ? phases.trace_camera : phases.trace_rest);
    if (depth == 0 && !f.aovs.empty()) add_camera_aovs(ctx, f);
    if (depth > 0) ctx.stats.bounce_rays += w.rays.size();
    ctx.stats.shadow_rays += w.shadows.size();
    add_unblocked_shadows(ctx);
    w.next_shadows.clear();
    w.next_rays.clear();
    sort_arrivals(ctx, depth);
    shade_double_vertices(ctx, depth);
    if (w.lane_vertices.count > 0) shade_lane_vertices(ctx, depth);
    w.rays.swap(w.next_rays);
    w.shadows.swap(w.next_shadows);
  }
  clock.lap(phases.shade);
  // Light sampling ran inside shading: its estimate (timed on a sample of calls, so it can
  // exceed the shading it is part of) is capped by the shading time and taken out of it.
  double shade_here = phases.shade - shade_at_start;
  double lights_here = std::min(phases.lights - lights_at_start, shade_here);
  phases.lights = lights_at_start + lights_here;
  phases.shade = shade_at_start + shade_here - lights_here;
  for (const PathState& p : w.paths) {
    if (!is_finite(p.radiance)) {
      ++ctx.stats.nonfinite_samples;
      continue;
    }
    for (int k = 0; k < 3; ++k)
      f.sum[p.pixel * 3 + k] += p.radiance[k];
  }
  clock.lap(phases.film);
}

void add_stats(PathStats& into, const PathStats& s) {
  into.phases.add(s.phases);
  into.camera_rays += s.camera_rays;
  into.bounce_rays += s.bounce_rays;
  into.shadow_rays += s.shadow_rays;
  into.nonfinite_samples += s.nonfinite_samples;
}

// CPU time of the calling thread: a tile's cost without the time the thread spent preempted
// (on a shared machine wall time made a few tiles look 8x their cost).
double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
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
  const LaneShading lanes{lane_materials, tracer.isa()};
  uint32_t tiles_x = (cam.width + kTile - 1) / kTile, tiles_y = (cam.height + kTile - 1) / kTile;
  const std::ptrdiff_t tiles = std::ptrdiff_t(tiles_x) * tiles_y;
  Film own;
  Film& f = film ? *film : own;
  if (f.sum.empty()) {
    f.width = cam.width, f.height = cam.height, f.passes = 0;
    f.sum.assign(std::size_t(cam.width) * cam.height * 3, 0.0);
    f.aovs = settings.aovs;
    f.aov_sum.assign(std::size_t(cam.width) * cam.height * std::size_t(f.aovs.channels()), 0.0);
  }
  PathStats total;
  total.passes = f.passes;
  auto start = std::chrono::steady_clock::now();
  // Each thread's wavefront lives across passes: regrown every pass, it cost 2-thread scaling.
  std::vector<Wavefront> per_thread(static_cast<std::size_t>(omp_get_max_threads()));
  TileShare share = settings.share;
  std::vector<double> tile_seconds(settings.reshare ? std::size_t(tiles) : 0);
  for (int pass = f.passes; pass < settings.spp; ++pass) {
#pragma omp parallel
    {
      // The team may be larger than omp_get_max_threads() said before it (seen under clang's
      // libomp with ASan: buffers for one thread, and a thread 1 in the team); the single's
      // barrier comes before any thread takes its buffers.
#pragma omp single
      if (per_thread.size() < std::size_t(omp_get_num_threads()))
        per_thread.resize(std::size_t(omp_get_num_threads()));
      PathStats local;
      Wavefront& wave = per_thread[std::size_t(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 1)
      for (std::ptrdiff_t t = 0; t < tiles; ++t) {
        if (!share.owns(uint64_t(t))) continue;
        if (settings.region &&
            !region_meets_tile(*settings.region, cam.width, cam.height, uint64_t(t)))
          continue;
        double started = tile_seconds.empty() ? 0 : thread_cpu_seconds();
        TileContext ctx{wave,     tracer, lights,
                        settings, lanes,  Rng::for_tile(settings.seed, t, pass),
                        {},       0,      uint32_t(pass)};
        PhaseClock clock(settings.time_phases);
        make_camera_rays(ctx, cam, uint32_t(t % tiles_x) * kTile, uint32_t(t / tiles_x) * kTile);
        clock.lap(ctx.stats.phases.camera);
        render_tile(ctx, f);
        if (!tile_seconds.empty()) tile_seconds[std::size_t(t)] = thread_cpu_seconds() - started;
        add_stats(local, ctx.stats);
      }
#pragma omp critical
      add_stats(total, local);
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