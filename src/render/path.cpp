#include "raylane/render/path.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <span>

#include <omp.h>

#include "raylane/core/ray_offset.h"
#include "raylane/render/bsdf.h"
#include "raylane/render/camera.h"
#include "raylane/render/film.h"
#include "raylane/render/lights.h"
#include "raylane/render/rng.h"
#include "raylane/render/sampling.h"
#include "raylane/render/shade_lanes.h"
#include "raylane/render/sobol.h"

namespace raylane {

namespace {

constexpr uint32_t kTile = 16;  // pixels per tile side: 256 paths per wavefront
constexpr uint32_t kBlock = 4;  // camera rays in 4×4 blocks: one coherent packet
constexpr double kRouletteSurvival = 0.8;

struct PathState {
  Rayd ray;
  Vec3d beta{1, 1, 1};  // throughput
  Vec3d radiance{0, 0, 0};
  Vec3d prev_p;                // the vertex the ray left (for the light pdf of MIS)
  double prev_pdf = 0;         // the BSDF density of the ray's direction
  bool prev_specular = false;  // ... drawn from a Dirac lobe: light sampling could not find it
  std::size_t pixel = 0;
  uint64_t pixel_seed = 0;  // the Sobol sampler's scramble of this pixel
};

struct ShadowQuery {
  uint32_t path;
  PrimRef light;
  Vec3d contribution;  // added to the path's radiance if the light is the first thing hit
};

// A phase timer that reads the clock only when the render asked for phase times.
class PhaseClock {
 public:
  explicit PhaseClock(bool on) : on_(on) {
    if (on_) last_ = std::chrono::steady_clock::now();
  }
  // Adds the time since the last lap to `into`.
  void lap(double& into) {
    if (!on_) return;
    auto now = std::chrono::steady_clock::now();
    into += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }

 private:
  bool on_;
  std::chrono::steady_clock::time_point last_;
};

// A thread's buffers, reused tile after tile: the render loop allocates nothing per sample
// once they have grown to a tile's size.
// A vertex waiting for the lanes: its row in the ShadeBatch is its index in `lane_rows`.
struct LaneRow {
  uint32_t path;  // index into the tile's paths
  uint32_t hit;   // index into the wavefront's hits
  LightSample light;
  double u_roulette;
  std::array<double, 4> u;        // the BSDF group: (u1, u2, lobe, roulette)
  std::array<double, 4> u_light;  // the light group: (u1, u2, light, part)
};

struct ThreadBuffers {
  std::vector<PathState> paths;
  std::vector<uint32_t> live, next_live;  // paths still going, by index
  std::vector<Rayd> batch, shadow_rays;
  std::vector<ShadowQuery> queries, next_queries;
  std::vector<Hit> hits;
  TraceScratch scratch;
  std::vector<LaneRow> lane_rows;  // rows [0, lane_count) are this wavefront's
  std::size_t lane_count = 0;
  ShadeBatch shade;
  SobolBatch sobol;
  LightQueries light_queries;
};

// What shading in lanes needs besides the settings (unused with Shading::kDouble).
struct LaneShading {
  const LaneMaterials& materials;
  Isa isa;
};

std::span<LaneRow> queued(ThreadBuffers& b) {
  return {b.lane_rows.data(), b.lane_count};
}

struct TileContext {
  ThreadBuffers& buffers;
  const Tracer& tracer;
  const LightSampler& lights;
  const PathSettings& settings;
  const LaneShading& lanes;
  Rng rng;
  PathStats stats;
  uint32_t light_calls;  // for timing one light sampling call in kLightTimingStride
  uint32_t pass;
};

// A path's decisions and the Sobol group each draws from (4 dimensions per group, the two
// that warp a direction or a point first, so that they get the (0, 2)-sequence's
// stratification). The MT19937 sampler ignores the groups and draws in call order.
struct Dims {
  static constexpr uint32_t camera = 0;  // (jitter x, jitter y, -, -)
  static uint32_t light(int depth) { return 1 + 2 * uint32_t(depth); }  // (u1, u2, light, part)
  static uint32_t bsdf(int depth) { return 2 + 2 * uint32_t(depth); }   // (u1, u2, lobe, roulette)
};

// A decision's numbers: the whole Sobol group at once, or, from MT19937, one number per
// component listed in `order`, drawn in that order (the order the course's code drew them).
std::array<double, 4> draw(TileContext& ctx, const PathState& p, uint32_t group,
                           std::initializer_list<int> order) {
  if (ctx.settings.sampler == Sampler::kSobol) return sobol_group(p.pixel_seed, ctx.pass, group);
  std::array<double, 4> u{};
  for (int c : order)
    u[c] = ctx.rng.uniform();
  return u;
}

// Roulette's number: the BSDF group's last component, drawn from MT19937 only when needed.
double roulette_uniform(TileContext& ctx, const std::array<double, 4>& bsdf_group) {
  return ctx.settings.sampler == Sampler::kSobol ? bsdf_group[3] : ctx.rng.uniform();
}

// Beer's law inside a transmissive solid (the course: exp(t·ln Kt) per channel, applied to the
// segment that ends on the inside of a surface). A material with Kt = 0 has no interior.
Vec3d beer(const Material& m, const Hit& hit) {
  Vec3d kt(m.kt);
  if (hit.front_face || kt == Vec3d(0, 0, 0)) return {1, 1, 1};
  Vec3d a;
  for (int k = 0; k < 3; ++k)
    a[k] = kt[k] > 0 ? std::exp(hit.t * std::log(kt[k])) : 0.0;
  return a;
}

// Jittered camera rays for one tile, 4×4 blocks at a time (y counts up in the pixel grid).
void tile_camera_rays(TileContext& ctx, const Camera& cam, uint32_t x0, uint32_t y0,
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
          auto u = draw(ctx, p, Dims::camera, {0, 1});
          p.ray = cam.ray_through(x + u[0], y + u[1]);
          paths.push_back(p);
        }
}

// What a path gains where it hits an emitter: all of it for a camera ray, for BSDF sampling
// alone or after a specular bounce (light sampling cannot reach a Dirac lobe); the MIS share
// after another bounce, nothing for NEE alone (light sampling counted it already).
void add_emission(TileContext& ctx, PathState& p, const Hit& hit, int depth) {
  Vec3d le = ctx.lights.emitted(hit);
  if (le == Vec3d(0, 0, 0)) return;
  double w = 1;
  bool sampled_light_too = depth > 0 && !p.prev_specular;
  if (sampled_light_too && ctx.settings.integrator == Integrator::kNee) w = 0;
  if (sampled_light_too && ctx.settings.integrator == Integrator::kMis)
    w = power_heuristic(p.prev_pdf, ctx.lights.pdf(p.prev_p, p.ray.d, hit));
  p.radiance += p.beta * le * w;
}

// Light sampling's time for --stats: the clock is read around one call in this many and that
// time scaled up; reading it around every call cost 15 % of the render and landed in this
// phase. (Shading's time has light sampling's estimate taken out, so it carries the error.)
constexpr uint32_t kLightTimingStride = 16;

// What one clock read costs, so that a timed interval can leave it out: scaled by the stride,
// it would otherwise add as much as the light sampling it measures. The median of a few
// thousand back-to-back reads.
double clock_read_seconds() {
  static const double cost = [] {
    constexpr int kReads = 4096;
    std::vector<double> gaps(kReads);
    auto last = std::chrono::steady_clock::now();
    for (double& g : gaps) {
      auto now = std::chrono::steady_clock::now();
      g = std::chrono::duration<double>(now - last).count();
      last = now;
    }
    std::nth_element(gaps.begin(), gaps.begin() + kReads / 2, gaps.end());
    return gaps[kReads / 2];
  }();
  return cost;
}

bool samples_lights(const TileContext& ctx) {
  return ctx.settings.integrator != Integrator::kBrdf && !ctx.lights.empty();
}

// Next-event estimation's point on a light, seen from this vertex, for the light group's
// numbers u (invalid: none).
LightSample sample_light_with(TileContext& ctx, const Hit& hit, const std::array<double, 4>& u) {
  bool timed = ctx.settings.time_phases && ctx.light_calls++ % kLightTimingStride == 0;
  PhaseClock clock(timed);
  LightSample ls = ctx.lights.sample(hit.surface.p, u[2], u[3], u[0], u[1]);
  if (timed) {
    double t = 0;
    clock.lap(t);
    ctx.stats.phases.lights += std::max(0.0, t - clock_read_seconds()) * kLightTimingStride;
  }
  return ls;
}

LightSample sample_light_point(TileContext& ctx, const PathState& p, const Hit& hit, int depth) {
  return sample_light_with(ctx, hit, draw(ctx, p, Dims::light(depth), {2, 3, 0, 1}));
}

// The shadow ray toward a sampled light point, given the BSDF's f·|cos θi| and density there.
void queue_shadow_ray(TileContext& ctx, uint32_t path, const PathState& p, const Hit& hit,
                      const LightSample& ls, const Vec3d& f, double bsdf_pdf) {
  if (f == Vec3d(0, 0, 0)) return;
  double w = ctx.settings.integrator == Integrator::kMis ? power_heuristic(ls.pdf, bsdf_pdf) : 1.0;
  Vec3d c = p.beta * f * ls.le * (w / ls.pdf);
  if (!is_finite(c)) return;
  Vec3d o = offset_ray_origin(hit.surface.p, hit_point_error(p.ray, hit.t), hit.surface.ng, ls.wi);
  ctx.buffers.shadow_rays.push_back({o, ls.wi});
  ctx.buffers.next_queries.push_back({path, ls.light, c});
}

// Where the path meets a surface: emission if it is an emitter (which ends the path, emitters
// reflect nothing), else Beer's law on the segment just travelled. The material's row if the
// path may scatter here.
std::optional<uint32_t> arrive(TileContext& ctx, PathState& p, const Hit& hit, int depth) {
  if (!hit.hit()) return std::nullopt;
  const Scene& scene = ctx.tracer.scene();
  uint32_t row = scene.material_of(hit.prim);
  const Material& m = scene.materials[row];
  if (m.is_light) {
    add_emission(ctx, p, hit, depth);
    return std::nullopt;
  }
  p.beta = p.beta * beer(m, hit);
  if (depth >= ctx.settings.max_depth) return std::nullopt;
  return row;
}

// After the BSDF's sample: the throughput, Russian roulette, the next ray. False when the
// path ends here.
bool continue_path(PathState& p, const Hit& hit, int depth, const BsdfSample& s, double u_roulette,
                   const PathSettings& settings) {
  if (!s.valid()) return false;
  p.beta = p.beta * s.value / s.pdf;
  if (depth + 1 >= settings.rr_depth) {
    if (u_roulette >= kRouletteSurvival) return false;
    p.beta = p.beta / kRouletteSurvival;
  }
  if (!is_finite(p.beta) || p.beta == Vec3d(0, 0, 0)) return false;
  p.prev_p = hit.surface.p;
  p.prev_pdf = s.pdf;
  p.prev_specular = s.specular;
  Vec3d o = offset_ray_origin(hit.surface.p, hit_point_error(p.ray, hit.t), hit.surface.ng, s.wi);
  p.ray = {o, s.wi};
  return true;
}

// One vertex with the double Bsdf: light sampling, then the next direction.
bool shade_vertex_double(TileContext& ctx, uint32_t path, PathState& p, const Hit& hit,
                         const Material& m, int depth) {
  Bsdf bsdf(m, hit.surface.ns, -p.ray.d);
  if (bsdf.black()) return false;
  if (samples_lights(ctx)) {
    LightSample ls = sample_light_point(ctx, p, hit, depth);
    if (ls.valid()) {
      BsdfEval e = bsdf.evaluate(ls.wi);
      queue_shadow_ray(ctx, path, p, hit, ls, e.f, e.pdf);
    }
  }
  auto u = draw(ctx, p, Dims::bsdf(depth), {2, 0, 1});
  BsdfSample s = bsdf.sample(u[2], u[0], u[1]);
  if (!s.valid()) return false;
  double u_roulette = depth + 1 >= ctx.settings.rr_depth ? roulette_uniform(ctx, u) : 0.0;
  return continue_path(p, hit, depth, s, u_roulette, ctx.settings);
}

// A vertex for the lanes (its numbers come in draw_lane_rows). Nothing when nothing reflects
// here.
void queue_lane_row(TileContext& ctx, uint32_t path, uint32_t hit_index, uint32_t material,
                    const PathState& p, const Hit& hit) {
  const LaneMaterials& lm = ctx.lanes.materials;
  double c = dot(hit.surface.ns, p.ray.d);
  if (c == 0 || !std::isfinite(c) || !(lm.pd[material] + lm.pr[material] + lm.pt[material] > 0))
    return;  // Bsdf::black()
  // Rows are reused, not built: a value-initialised LaneRow (176 bytes) per vertex cost 4 % of
  // a render in zeroing and copying. draw_lane_rows sets the rest.
  ThreadBuffers& b = ctx.buffers;
  if (b.lane_count == b.lane_rows.size()) b.lane_rows.emplace_back();
  LaneRow& row = b.lane_rows[b.lane_count++];
  row.path = path, row.hit = hit_index;
  row.light.pdf = 0;
}

// The queued vertices' light points, all at once (sphere lights in lanes).
void sample_lights_in_lanes(TileContext& ctx) {
  ThreadBuffers& b = ctx.buffers;
  PhaseClock clock(ctx.settings.time_phases);
  LightQueries& q = b.light_queries;
  q.resize(b.lane_count);
  for (std::size_t r = 0; r < b.lane_count; ++r) {
    q.ref[r] = b.hits[b.lane_rows[r].hit].surface.p;
    q.u[r] = b.lane_rows[r].u_light;
  }
  ctx.lights.sample_many(ctx.lanes.isa, q);
  for (std::size_t r = 0; r < b.lane_count; ++r)
    b.lane_rows[r].light = q.out[r];
  clock.lap(ctx.stats.phases.lights);
}

// The numbers of one Sobol group for every queued vertex, from the lanes.
template <class Store>
void sobol_for_rows(TileContext& ctx, uint32_t group, Store store) {
  SobolBatch& sb = ctx.buffers.sobol;
  sobol_groups(ctx.lanes.isa, ctx.pass, group, sb);
  for (std::size_t r = 0; r < ctx.buffers.lane_count; ++r)
    store(ctx.buffers.lane_rows[r],
          std::array<double, 4>{sb.u[0][r] * 0x1p-32, sb.u[1][r] * 0x1p-32, sb.u[2][r] * 0x1p-32,
                                sb.u[3][r] * 0x1p-32});
}

// The queued vertices' numbers — Sobol groups for all of them at once in lanes, or MT19937
// row by row in the double shading's order (light, BSDF, roulette) — then their light points.
void draw_lane_rows(TileContext& ctx, int depth) {
  ThreadBuffers& b = ctx.buffers;
  const bool lights = samples_lights(ctx), roulette = depth + 1 >= ctx.settings.rr_depth;
  if (ctx.settings.sampler == Sampler::kSobol) {
    b.sobol.resize(b.lane_count);
    for (std::size_t r = 0; r < b.lane_count; ++r)
      b.sobol.seed[r] = b.paths[b.lane_rows[r].path].pixel_seed;
    if (lights)
      sobol_for_rows(ctx, Dims::light(depth), [](LaneRow& row, auto u) { row.u_light = u; });
    sobol_for_rows(ctx, Dims::bsdf(depth), [](LaneRow& row, auto u) {
      row.u = u;
      row.u_roulette = u[3];
    });
  } else {
    for (LaneRow& row : queued(b)) {
      const PathState& p = b.paths[row.path];
      if (lights) row.u_light = draw(ctx, p, Dims::light(depth), {2, 3, 0, 1});
      row.u = draw(ctx, p, Dims::bsdf(depth), {2, 0, 1});
      if (roulette) row.u_roulette = ctx.rng.uniform();
    }
  }
  if (lights) sample_lights_in_lanes(ctx);
}

// The queued vertices' BSDFs in one lane batch, then each vertex's shadow ray and next ray.
void shade_in_lanes(TileContext& ctx, int depth) {
  ThreadBuffers& b = ctx.buffers;
  draw_lane_rows(ctx, depth);
  ShadeBatch& sb = b.shade;
  sb.resize(b.lane_count);
  const Scene& scene = ctx.tracer.scene();
  for (std::size_t r = 0; r < b.lane_count; ++r) {
    const LaneRow& row = b.lane_rows[r];
    const Hit& hit = b.hits[row.hit];
    const Vec3d wo = -b.paths[row.path].ray.d;
    sb.material[r] = int32_t(scene.material_of(hit.prim));
    const Vec3d light_wi = row.light.valid() ? row.light.wi : Vec3d(0, 0, 0);
    for (int k = 0; k < 3; ++k) {
      sb.n[k][r] = float(hit.surface.ns[k]);
      sb.wo[k][r] = float(wo[k]);
      sb.light_wi[k][r] = float(light_wi[k]);
    }
    sb.u_lobe[r] = float(row.u[2]), sb.u1[r] = float(row.u[0]), sb.u2[r] = float(row.u[1]);
  }
  shade_lanes(ctx.lanes.isa, ctx.lanes.materials, sb);
  for (std::size_t r = 0; r < b.lane_count; ++r) {
    const LaneRow& row = b.lane_rows[r];
    PathState& p = b.paths[row.path];
    const Hit& hit = b.hits[row.hit];
    if (row.light.valid()) {
      Vec3d f(sb.light_f[0][r], sb.light_f[1][r], sb.light_f[2][r]);
      queue_shadow_ray(ctx, row.path, p, hit, row.light, f, sb.light_pdf[r]);
    }
    BsdfSample s;
    s.wi = Vec3d(sb.wi[0][r], sb.wi[1][r], sb.wi[2][r]);
    s.value = Vec3d(sb.value[0][r], sb.value[1][r], sb.value[2][r]);
    s.pdf = sb.pdf[r];
    if (continue_path(p, hit, depth, s, row.u_roulette, ctx.settings))
      b.next_live.push_back(row.path);
  }
}

// Shades the wavefront's vertices: each live path's hit, in lanes where the settings and the
// material allow, one by one in double otherwise. Fills next_live, shadow_rays, next_queries.
void shade_wavefront(TileContext& ctx, int depth) {
  ThreadBuffers& b = ctx.buffers;
  b.lane_count = 0;
  const bool lanes = ctx.settings.shading == Shading::kFloat;
  for (std::size_t k = 0; k < b.live.size(); ++k) {
    uint32_t path = b.live[k];
    PathState& p = b.paths[path];
    const Hit& hit = b.hits[k];
    std::optional<uint32_t> material = arrive(ctx, p, hit, depth);
    if (!material) continue;
    if (lanes && ctx.lanes.materials.in_lanes[*material]) {
      queue_lane_row(ctx, path, uint32_t(k), *material, p, hit);
      continue;
    }
    const Material& m = ctx.tracer.scene().materials[*material];
    if (shade_vertex_double(ctx, path, p, hit, m, depth)) b.next_live.push_back(path);
  }
  if (b.lane_count > 0) shade_in_lanes(ctx, depth);
}

// One sample for every pixel of a tile, bounce by bounce. Each wavefront holds the
// continuation rays of the live paths and the shadow rays of the previous vertices.
void render_tile(TileContext& ctx, std::vector<double>& film) {
  ThreadBuffers& b = ctx.buffers;
  auto& [paths, live, next_live, batch, shadow_rays, queries, next_queries, hits, scratch,
         lane_rows, lane_count, shade, sobol, light_queries] = b;
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
    batch.clear();
    for (uint32_t i : live)
      batch.push_back(paths[i].ray);
    batch.insert(batch.end(), shadow_rays.begin(), shadow_rays.end());
    clock.lap(phases.shade);
    ctx.tracer.closest(batch, hits, live.size(), scratch);  // shadow rays need no surface
    clock.lap(depth == 0 ? phases.trace_camera : phases.trace_rest);
    if (depth > 0) ctx.stats.bounce_rays += live.size();
    ctx.stats.shadow_rays += queries.size();
    for (std::size_t q = 0; q < queries.size(); ++q) {
      Hit& h = hits[live.size() + q];
      // Visible when the first thing met is the light's emitting side (convex solids are
      // sampled on faces toward the vertex only, so no other face of theirs is in between).
      bool seen = h.hit() && h.prim == queries[q].light;
      if (seen && !kind_two_sided(h.prim.tag()))
        seen = ctx.tracer.front_face(batch[live.size() + q], h);
      if (seen) paths[queries[q].path].radiance += queries[q].contribution;
    }
    shadow_rays.clear();
    next_queries.clear();
    next_live.clear();
    shade_wavefront(ctx, depth);
    live.swap(next_live);
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
    f.fingerprint = film_fingerprint(scene, settings);
    f.origin = film_origin(scene, settings);
  }
  PathStats total;
  total.passes = f.passes;
  auto start = std::chrono::steady_clock::now();
  // Each thread's buffers live across passes: regrown every pass, they cost 2-thread scaling.
  std::vector<ThreadBuffers> per_thread(static_cast<std::size_t>(omp_get_max_threads()));
  for (int pass = f.passes; pass < settings.spp; ++pass) {
#pragma omp parallel
    {
      PathStats local;
      ThreadBuffers& buffers = per_thread[std::size_t(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 1)
      for (std::ptrdiff_t t = 0; t < tiles; ++t) {
        TileContext ctx{buffers,  tracer, lights,
                        settings, lanes,  Rng::for_tile(settings.seed, t, pass),
                        {},       0,      uint32_t(pass)};
        PhaseClock clock(settings.time_phases);
        tile_camera_rays(ctx, cam, uint32_t(t % tiles_x) * kTile, uint32_t(t / tiles_x) * kTile,
                         buffers.paths);
        clock.lap(ctx.stats.phases.camera);
        render_tile(ctx, f.sum);
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
  }
  if (stats) *stats = total;
  return f.image();
}

}  // namespace raylane
