#include "raylane/render/path.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <utility>

#include <omp.h>

#include "raylane/render/camera.h"
#include "raylane/render/film.h"
#include "raylane/render/texturing.h"
#include "render/path_loop.h"

namespace raylane {

using namespace path_detail;

namespace {

// A tile's paths, 4×4 blocks of pixels at a time (y counts up in the pixel grid), before their
// camera rays: pixel and Sobol scramble.
void tile_paths(TileContext& ctx, const Camera& cam, uint32_t x0, uint32_t y0,
                std::vector<PathState>& paths) {
  paths.clear();
  uint32_t x1 = std::min(x0 + kTile, cam.width), y1 = std::min(y0 + kTile, cam.height);
  for (uint32_t by = y0; by < y1; by += kBlock)
    for (uint32_t bx = x0; bx < x1; bx += kBlock)
      for (uint32_t y = by; y < std::min(by + kBlock, y1); ++y)
        for (uint32_t x = bx; x < std::min(bx + kBlock, x1); ++x) {
          PathState p;
          p.pixel = std::size_t(cam.height - 1 - y) * cam.width + x;
          p.pixel_seed = mix64(ctx.settings.seed ^ mix64(p.pixel));
          paths.push_back(p);
        }
}

// Jittered camera rays for a tile's paths (rays[i] for paths[i]). Sobol's camera groups come from
// the lanes for the whole tile at once (bit for bit sobol_group); MT19937 draws pixel by pixel.
void tile_camera_rays(TileContext& ctx, const Camera& cam, uint32_t x0, uint32_t y0,
                      std::vector<PathState>& paths, RayStream& rays) {
  tile_paths(ctx, cam, x0, y0, paths);
  rays.clear();
  rays.resize(paths.size());
  const bool sobol = ctx.settings.sampler == Sampler::kSobol;
  SobolBatch& s = ctx.buffers.sobol;
  if (sobol) {
    s.resize(paths.size());
    for (std::size_t i = 0; i < paths.size(); ++i)
      s.seed[i] = paths[i].pixel_seed;
    sobol_groups(ctx.lanes.isa, ctx.pass, Dims::camera, s);
  }
  for (std::size_t i = 0; i < paths.size(); ++i) {
    PathState& p = paths[i];
    std::array<double, 4> u;
    if (sobol)
      for (int c = 0; c < 4; ++c)
        u[std::size_t(c)] = s.u[std::size_t(c)][i] * 0x1p-32;
    else  // the lens's numbers only with a lens: a pinhole render draws what it always drew
      u = cam.has_lens() ? draw(ctx, p, Dims::camera, {0, 1, 2, 3})
                         : draw(ctx, p, Dims::camera, {0, 1});
    double x = double(p.pixel % cam.width), y = double(cam.height - 1 - p.pixel / cam.width);
    rays.set(i, ray_cast<float>(cam.ray_through_lens(x + u[0], y + u[1], u[2], u[3])));
  }
}

// The AOVs of a tile's camera samples (render/aov.h), from the first wavefront's hits: there
// hits[i] belongs to paths[i]. A sample that meets nothing adds zeros.
void add_aovs(const Scene& scene, const std::vector<PathState>& paths, const std::vector<Hit>& hits,
              Film& film) {
  const AovSet set = film.aovs;
  const std::size_t stride = std::size_t(set.channels());
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const Hit& h = hits[i];
    if (!h.hit()) continue;
    double* out = &film.aov_sum[paths[i].pixel * stride];
    auto add = [&](Aov a, const Vec3d& v) {
      if (!set.has(a)) return;
      double* at = out + set.offset(a);
      for (int k = 0; k < aov_channels(a); ++k)
        at[k] += v[k];
    };
    if (set.has(Aov::kAlbedo)) add(Aov::kAlbedo, albedo_at(scene, h.prim, h.surface));
    add(Aov::kNormal, h.surface.ns);
    add(Aov::kDepth, {h.t, h.t, h.t});
    add(Aov::kPosition, h.surface.p);
  }
}

// One sample for every pixel of a tile, bounce by bounce. Each wavefront holds the
// continuation rays of the live paths and the shadow rays of the previous vertices.
void render_tile(TileContext& ctx, Film& f) {
  std::vector<double>& film = f.sum;
  ThreadBuffers& b = ctx.buffers;
  std::vector<PathState>& paths = b.paths;
  std::vector<uint32_t>&live = b.live, &next_live = b.next_live;
  RayStream &rays = b.rays, &shadow_rays = b.shadow_rays;
  ShadowQueries &queries = b.queries, &next_queries = b.next_queries;
  std::vector<Hit>& hits = b.hits;
  live.resize(paths.size());
  for (uint32_t i = 0; i < live.size(); ++i)
    live[i] = i;
  shadow_rays.clear();
  queries.clear();
  ctx.stats.camera_rays += paths.size();
  PathPhases& phases = ctx.stats.phases;
  const double lights_at_start = phases.lights, shade_at_start = phases.shade;
  PhaseClock clock(ctx.settings.time_phases);
  for (int depth = 0; !live.empty() || !queries.empty(); ++depth) {
    clock.lap(phases.shade);
    // Surfaces for every hit only where they are all read: the double shading's vertices, the
    // AOVs of the camera hits. Otherwise prim and t alone, and the surfaces of the vertices that
    // need one follow: the lanes' into their columns (Tracer::surfaces), the rest one by one.
    const bool all_surfaces = ctx.settings.shading == Shading::kDouble ||
                              (depth == 0 && !f.aovs.empty()) ||
                              ctx.tracer.kind() != TracerKind::kPacket;
    ctx.tracer.closest(rays, hits, all_surfaces ? rays.size() : 0, b.scratch);
    b.hits_have_surfaces = all_surfaces;
    // Shadow rays, aimed at their light: it is seen when nothing else lies before it.
    ctx.tracer.occluded(shadow_rays, b.blocked, b.scratch);
    clock.lap(depth == 0 ? phases.trace_camera : phases.trace_rest);
    if (depth == 0 && !f.aovs.empty()) add_aovs(ctx.tracer.scene(), paths, hits, f);
    if (depth > 0) ctx.stats.bounce_rays += live.size();
    ctx.stats.shadow_rays += queries.size();
    for (std::size_t q = 0; q < queries.size(); ++q)
      if (b.blocked[q] == 0) paths[queries.path[q]].radiance += queries.contribution_of(q);
    shadow_rays.clear();
    next_queries.clear();
    next_live.clear();
    b.next_rays.clear();
    shade_wavefront(ctx, depth);
    live.swap(next_live);
    std::swap(rays, b.next_rays);
    queries.swap(next_queries);
  }
  clock.lap(phases.shade);
  // Light sampling ran inside shading: its estimate (timed on a sample of calls, so it can
  // exceed the shading it is part of) is capped by the shading time and taken out of it.
  double shade_here = phases.shade - shade_at_start;
  double lights_here = std::min(phases.lights - lights_at_start, shade_here);
  phases.lights = lights_at_start + lights_here;
  phases.shade = shade_at_start + shade_here - lights_here;
  for (const PathState& p : paths) {
    if (!is_finite(p.radiance)) {
      ++ctx.stats.nonfinite_samples;
      continue;
    }
    for (int k = 0; k < 3; ++k)
      film[p.pixel * 3 + k] += p.radiance[k];
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
  // Each thread's buffers live across passes: regrown every pass, they cost 2-thread scaling.
  std::vector<ThreadBuffers> per_thread(static_cast<std::size_t>(omp_get_max_threads()));
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
      ThreadBuffers& buffers = per_thread[std::size_t(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 1)
      for (std::ptrdiff_t t = 0; t < tiles; ++t) {
        if (!share.owns(uint64_t(t))) continue;
        if (settings.region &&
            !region_meets_tile(*settings.region, cam.width, cam.height, uint64_t(t)))
          continue;
        double started = tile_seconds.empty() ? 0 : thread_cpu_seconds();
        TileContext ctx{buffers,  tracer, lights,
                        settings, lanes,  Rng::for_tile(settings.seed, t, pass),
                        {},       0,      uint32_t(pass)};
        PhaseClock clock(settings.time_phases);
        tile_camera_rays(ctx, cam, uint32_t(t % tiles_x) * kTile, uint32_t(t / tiles_x) * kTile,
                         buffers.paths, buffers.rays);
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