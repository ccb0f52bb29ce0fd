#include "raylane/render/path.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <initializer_list>

#include "raylane/core/ray_offset.h"
#include "raylane/render/bsdf.h"
#include "raylane/render/camera.h"
#include "raylane/render/film.h"
#include "raylane/render/lights.h"
#include "raylane/render/rng.h"
#include "raylane/render/sampling.h"
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
struct ThreadBuffers {
  std::vector<PathState> paths;
  std::vector<uint32_t> live, next_live;  // paths still going, by index
  std::vector<Rayd> batch, shadow_rays;
  std::vector<ShadowQuery> queries, next_queries;
  std::vector<Hit> hits;
  TraceScratch scratch;
};

struct TileContext {
  ThreadBuffers& buffers;
  const Tracer& tracer;
  const LightSampler& lights;
  const PathSettings& settings;
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

const Material& material_of(const Scene& scene, const Hit& hit) {
  return scene.materials[scene.material_of(hit.prim)];
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

// Next-event estimation from one vertex: a shadow ray toward a sampled light point.
void sample_light_untimed(TileContext& ctx, uint32_t path, const PathState& p, const Bsdf& bsdf,
                          const Hit& hit, int depth, std::vector<Rayd>& rays,
                          std::vector<ShadowQuery>& queries) {
  auto u = draw(ctx, p, Dims::light(depth), {2, 3, 0, 1});
  LightSample ls = ctx.lights.sample(hit.surface.p, u[2], u[3], u[0], u[1]);
  if (!ls.valid()) return;
  BsdfEval e = bsdf.evaluate(ls.wi);
  if (e.f == Vec3d(0, 0, 0)) return;
  double w = ctx.settings.integrator == Integrator::kMis ? power_heuristic(ls.pdf, e.pdf) : 1.0;
  Vec3d c = p.beta * e.f * ls.le * (w / ls.pdf);
  if (!is_finite(c)) return;
  Vec3d o = offset_ray_origin(hit.surface.p, hit_point_error(p.ray, hit.t), hit.surface.ng, ls.wi);
  rays.push_back({o, ls.wi});
  queries.push_back({path, ls.light, c});
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

void sample_light(TileContext& ctx, uint32_t path, const PathState& p, const Bsdf& bsdf,
                  const Hit& hit, int depth, std::vector<Rayd>& rays,
                  std::vector<ShadowQuery>& queries) {
  bool timed = ctx.settings.time_phases && ctx.light_calls++ % kLightTimingStride == 0;
  PhaseClock clock(timed);
  sample_light_untimed(ctx, path, p, bsdf, hit, depth, rays, queries);
  if (!timed) return;
  double t = 0;
  clock.lap(t);
  ctx.stats.phases.lights += std::max(0.0, t - clock_read_seconds()) * kLightTimingStride;
}

// One vertex of a path: emission, absorption, light sampling, then the next direction.
// Returns false when the path ends here.
bool shade_vertex(TileContext& ctx, uint32_t path, PathState& p, const Hit& hit, int depth,
                  std::vector<Rayd>& shadow_rays, std::vector<ShadowQuery>& queries) {
  if (!hit.hit()) return false;
  const Material& m = material_of(ctx.tracer.scene(), hit);
  if (m.is_light) {
    add_emission(ctx, p, hit, depth);
    return false;  // emitters reflect nothing
  }
  p.beta = p.beta * beer(m, hit);
  Vec3d wo = -p.ray.d;
  Bsdf bsdf(m, hit.surface.ns, wo);
  if (bsdf.black() || depth >= ctx.settings.max_depth) return false;
  if (ctx.settings.integrator != Integrator::kBrdf && !ctx.lights.empty())
    sample_light(ctx, path, p, bsdf, hit, depth, shadow_rays, queries);
  auto u = draw(ctx, p, Dims::bsdf(depth), {2, 0, 1});
  BsdfSample s = bsdf.sample(u[2], u[0], u[1]);
  if (!s.valid()) return false;
  p.beta = p.beta * s.value / s.pdf;
  if (depth + 1 >= ctx.settings.rr_depth) {
    if (roulette_uniform(ctx, u) >= kRouletteSurvival) return false;
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

// One sample for every pixel of a tile, bounce by bounce. Each wavefront holds the
// continuation rays of the live paths and the shadow rays of the previous vertices.
void render_tile(TileContext& ctx, std::vector<double>& film) {
  ThreadBuffers& b = ctx.buffers;
  auto& [paths, live, next_live, batch, shadow_rays, queries, next_queries, hits, scratch] = b;
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
      if (seen && !kind_two_sided(h.prim.tag())) {
        ctx.tracer.complete(batch[live.size() + q], h);
        seen = h.front_face;
      }
      if (seen) paths[queries[q].path].radiance += queries[q].contribution;
    }
    shadow_rays.clear();
    next_queries.clear();
    next_live.clear();
    for (std::size_t k = 0; k < live.size(); ++k)
      if (shade_vertex(ctx, live[k], paths[live[k]], hits[k], depth, shadow_rays, next_queries))
        next_live.push_back(live[k]);
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
  for (int pass = f.passes; pass < settings.spp; ++pass) {
#pragma omp parallel
    {
      PathStats local;
      ThreadBuffers buffers;
#pragma omp for schedule(dynamic, 1)
      for (std::ptrdiff_t t = 0; t < tiles; ++t) {
        TileContext ctx{
            buffers, tracer, lights,        settings, Rng::for_tile(settings.seed, t, pass),
            {},      0,      uint32_t(pass)};
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
