#include "render/wavefront/render_loop.h"

#include <algorithm>
#include <ctime>

namespace raylane::path_detail {

namespace {

constexpr uint32_t kTilePaths = kTile * kTile;  // path slots per block
constexpr unsigned kTileShift = 8;              // path >> kTileShift: its block
static_assert(kTilePaths == 1u << kTileShift);

// CPU time of the calling thread: a tile's cost without the time the thread spent preempted
// (on a shared machine wall time made a few tiles look 8x their cost).
double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

// A free block of path slots (a new one if every block holds a tile still going).
TileInFlight& free_block(Wavefront& w) {
  for (TileInFlight& t : w.tiles)
    if (t.tile < 0) return t;
  TileInFlight& t = w.tiles.emplace_back();
  t.first = uint32_t(w.tiles.size() - 1) * kTilePaths;
  return t;
}

// Whether the wavefront takes another tile now.
bool has_room(const ThreadContext& ctx) {
  const Wavefront& w = ctx.wave;
  if (ctx.settings.sampler != Sampler::kSobol || !ctx.settings.refill)
    return w.rays.empty() && w.shadows.empty();
  return w.rays.size() < kRefillBelow;
}

// Tiles while there is room: each one's paths into a free block, its camera rays in front of
// the rays already waiting (so that they stay whole 4×4 packets; Wavefront::camera_rays counts
// them).
void claim_tiles(ThreadContext& ctx, const Camera& cam, TileClaims& claims) {
  Wavefront& w = ctx.wave;
  w.camera_rays = 0;
  std::ptrdiff_t t = 0;
  while (has_room(ctx) && claims.next(t)) {
    TileInFlight& tile = free_block(w);
    ctx.rng = Rng::for_tile(ctx.settings.seed, uint64_t(t), ctx.pass);
    const uint32_t x0 = uint32_t(t % claims.tiles_x()) * kTile;
    const uint32_t y0 = uint32_t(t / claims.tiles_x()) * kTile;
    tile.tile = t, tile.seconds = 0;
    tile.paths = make_camera_rays(ctx, cam, x0, y0, tile.first, w.next_rays);
    tile.live = tile.paths;
    ctx.stats.camera_rays += tile.paths;
    w.camera_rays += tile.paths;
    w.next_rays.append(w.rays);
    w.rays.swap(w.next_rays);
  }
}

// The records' primitives and t as columns (t rounded to float: a reference tracer's double t
// stays in its record).
void hits_from_records(const std::vector<Hit>& records, HitStream& hits) {
  hits.resize(records.size());
  for (std::size_t k = 0; k < records.size(); ++k)
    hits.t[k] = float(records[k].t), hits.prim[k] = records[k].prim.bits();
}

// One step of the wavefront: trace its rays and shadow rays, then the stages that fill the
// next step's queues.
void step(ThreadContext& ctx, Film& f) {
  Wavefront& w = ctx.wave;
  PathPhases& phases = ctx.stats.phases;
  const double lights_at_start = phases.lights;
  PhaseClock clock(ctx.settings.time_phases);
  // Surfaces for every hit only where they are all read: the double shading's vertices, the
  // AOVs of the camera hits. Otherwise prim and t alone, and the surfaces of the vertices that
  // need one follow: the lanes' into their columns (Tracer::surfaces), the rest one by one.
  const bool camera_aovs = w.camera_rays > 0 && !f.aovs.empty();
  const bool all_surfaces = ctx.settings.shading == Shading::kDouble || camera_aovs ||
                            ctx.tracer.backend() != TracerBackend::kPacket;
  stamp_times(ctx);
  w.records.clear();
  if (all_surfaces) {
    ctx.tracer.closest(w.rays.rays, w.records, w.rays.size(), w.scratch);
    hits_from_records(w.records, w.hits);
  } else {
    ctx.tracer.closest(w.rays.rays, w.hits, w.scratch);
  }
  // Shadow rays, aimed at their light: it is seen when nothing else lies before it.
  ctx.tracer.occluded(w.shadows.rays, w.blocked, w.scratch);
  double traced = 0;
  clock.lap(traced);
  // Camera rays and the rest share the tracing time by their counts.
  const double camera_share = double(w.camera_rays) / double(w.rays.size() + w.shadows.size());
  phases.trace_camera += traced * camera_share;
  phases.trace_rest += traced * (1 - camera_share);
  if (camera_aovs) add_camera_aovs(ctx, f);
  ctx.stats.bounce_rays += w.rays.size() - w.camera_rays;
  ctx.stats.shadow_rays += w.shadows.size();
  ++ctx.stats.steps;
  add_unblocked_shadows(ctx);
  w.next_shadows.clear();
  w.next_rays.clear();
  sort_arrivals(ctx);
  shade_double_vertices(ctx);
  if (w.lane_vertices.count > 0) shade_lane_vertices(ctx);
  w.rays.swap(w.next_rays);
  w.shadows.swap(w.next_shadows);
  double shaded = 0;
  clock.lap(shaded);
  // Light sampling ran inside shading: its estimate (timed on a sample of calls, so it can
  // exceed the shading it is part of) is capped by the shading time and taken out of it.
  const double lights = std::min(phases.lights - lights_at_start, shaded);
  phases.lights = lights_at_start + lights;
  phases.shade += shaded - lights;
}

// A finished tile's samples into the film (each pixel gets one per pass, so the order of the
// tiles does not matter).
void add_to_film(ThreadContext& ctx, const TileInFlight& tile, Film& f) {
  const PathState* paths = ctx.wave.paths.data() + tile.first;
  for (uint32_t i = 0; i < tile.paths; ++i) {
    const PathState& p = paths[i];
    if (!is_finite(p.radiance)) {
      ++ctx.stats.nonfinite_samples;
      continue;
    }
    const std::size_t at = f.slot(p.pixel);
    if (at == Film::kNotStored) continue;  // outside the region, in one of its tiles
    for (int k = 0; k < 3; ++k)
      f.sum[at * 3 + k] += p.radiance[k];
  }
}

// Each tile's `live`: its rays and shadow rays waiting, counted where they are read (MPI's tile
// costs) or where the blocks outnumber a word's bits; else 1 for a tile that has any.
void mark_live_tiles(const ThreadContext& ctx, Wavefront& w, bool counted) {
  for (TileInFlight& t : w.tiles)
    t.live = 0;
  if (counted || w.tiles.size() > 64) {
    for (uint32_t p : w.rays.path)
      ++w.tiles[p / kTilePaths].live;
    for (uint32_t p : w.shadows.path)
      ++w.tiles[p / kTilePaths].live;
    return;
  }
  // The blocks holding a path as bits (block b: bit b; at most 64 blocks), ORed in lanes:
  // counting into each tile's `live` chained every increment on the one before through
  // memory, and a scalar loop paid a shift and an OR per path.
  auto blocks_of = [&](const Column<uint32_t>& paths) {
    return ctx.lanes.kernels.blocks_of_paths(paths.data(), paths.size(), kTileShift);
  };
  const uint64_t blocks = blocks_of(w.rays.path) | blocks_of(w.shadows.path);
  for (std::size_t b = 0; b < w.tiles.size(); ++b)
    w.tiles[b].live = uint32_t(blocks >> b & 1u);
}

// The step's CPU time shared by the tiles by their rays in it; then the tiles that have rays
// for the next step marked, and the others finished (their samples into the film, their blocks
// freed).
void finish_tiles(ThreadContext& ctx, Film& f, double step_seconds,
                  std::vector<double>& tile_seconds) {
  Wavefront& w = ctx.wave;
  if (!tile_seconds.empty()) {
    std::size_t rays = 0;
    for (const TileInFlight& t : w.tiles)
      rays += t.tile >= 0 ? t.live : 0;
    for (TileInFlight& t : w.tiles)
      if (t.tile >= 0 && rays > 0) t.seconds += step_seconds * double(t.live) / double(rays);
  }
  mark_live_tiles(ctx, w, !tile_seconds.empty());
  PhaseClock clock(ctx.settings.time_phases);
  for (TileInFlight& t : w.tiles) {
    if (t.tile < 0 || t.live > 0) continue;
    add_to_film(ctx, t, f);
    if (!tile_seconds.empty()) tile_seconds[std::size_t(t.tile)] = t.seconds;
    t.tile = -1;
  }
  clock.lap(ctx.stats.phases.film);
}

}  // namespace

TileClaims::TileClaims(const Camera& cam, const TileShare& share, const PathSettings& settings)
    : tiles_x_((cam.width + kTile - 1) / kTile),
      width_(cam.width),
      height_(cam.height),
      share_(share),
      settings_(settings) {
  tiles_ = std::ptrdiff_t(tiles_x_) * std::ptrdiff_t((cam.height + kTile - 1) / kTile);
}

bool TileClaims::next(std::ptrdiff_t& tile) {
  for (;;) {
    tile = next_.fetch_add(1, std::memory_order_relaxed);
    if (tile >= tiles_) return false;
    if (!share_.owns(uint64_t(tile))) continue;
    if (settings_.region && !region_meets_tile(*settings_.region, width_, height_, uint64_t(tile)))
      continue;
    return true;
  }
}

void render_claimed_tiles(ThreadContext& ctx, const Camera& cam, TileClaims& claims, Film& film,
                          std::vector<double>& tile_seconds) {
  Wavefront& w = ctx.wave;
  w.rays.clear(), w.shadows.clear();
  for (TileInFlight& t : w.tiles)
    t.tile = -1;
  for (;;) {
    PhaseClock clock(ctx.settings.time_phases);
    claim_tiles(ctx, cam, claims);
    clock.lap(ctx.stats.phases.camera);
    if (w.rays.empty() && w.shadows.empty()) return;
    const double started = tile_seconds.empty() ? 0 : thread_cpu_seconds();
    step(ctx, film);
    const double seconds = tile_seconds.empty() ? 0 : thread_cpu_seconds() - started;
    finish_tiles(ctx, film, seconds, tile_seconds);
  }
}

}  // namespace raylane::path_detail
