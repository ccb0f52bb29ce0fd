// One vertex at a time with the double Bsdf, and what both shadings share: emission, Beer's
// law, light sampling's timing, shadow rays, roulette and the next ray (render/path_loop.h).
#include <algorithm>
#include <cmath>

#include "raylane/core/ray_offset.h"
#include "raylane/render/sampling.h"
#include "raylane/render/texturing.h"
#include "render/path_loop.h"

namespace raylane::path_detail {

namespace {

// Roulette's number: the BSDF group's last component, drawn from MT19937 only when needed.
double roulette_uniform(TileContext& ctx, const std::array<double, 4>& bsdf_group) {
  return ctx.settings.sampler == Sampler::kSobol ? bsdf_group[3] : ctx.rng.uniform();
}

// What a path gains where it hits an emitter: all of it for a camera ray, for BSDF sampling
// alone or after a specular bounce (light sampling cannot reach a Dirac lobe); the MIS share
// after another bounce, nothing for NEE alone (light sampling counted it already).
void add_emission(TileContext& ctx, PathState& p, const Rayd& ray, const Hit& hit, int depth) {
  Vec3d le = ctx.lights.emitted(hit);
  if (le == Vec3d(0, 0, 0)) return;
  double w = 1;
  bool sampled_light_too = depth > 0 && !p.prev_specular;
  if (sampled_light_too && ctx.settings.integrator == Integrator::kNee) w = 0;
  if (sampled_light_too && ctx.settings.integrator == Integrator::kMis)
    w = power_heuristic(p.prev_pdf, ctx.lights.pdf(p.prev_p, ray.d, hit));
  p.radiance += p.beta * le * w;
}

// What a path gains when its ray leaves the scene: the environment, weighted as add_emission
// weighs an emitter (its density for MIS is the environment's).
void add_escape(TileContext& ctx, PathState& p, const Rayd& ray, int depth) {
  Vec3d le = ctx.lights.escaped(ray.d);
  if (le == Vec3d(0, 0, 0)) return;
  double w = 1;
  bool sampled_light_too = depth > 0 && !p.prev_specular;
  if (sampled_light_too && ctx.settings.integrator == Integrator::kNee) w = 0;
  if (sampled_light_too && ctx.settings.integrator == Integrator::kMis)
    w = power_heuristic(p.prev_pdf, ctx.lights.environment_pdf(ray.d));
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

// The hit's surface, if closest() gave prim and t alone.
void ensure_surface(TileContext& ctx, const Rayd& ray, Hit& hit) {
  if (!ctx.buffers.hits_have_surfaces) ctx.tracer.complete(ray, hit);
}

// Where the path meets a surface (the hit of wavefront ray k): emission if it is an emitter
// (which ends the path, emitters reflect nothing). The material's row if the path may scatter
// here. (Beer's law on the segment just travelled is the caller's: lanes apply it with the
// surfaces they compute. A path that ends here needs none: nothing reads its throughput
// again.) The ray is widened only where it is read: the lane rows take theirs with their
// surfaces.
std::optional<uint32_t> arrive(TileContext& ctx, PathState& p, std::size_t k, Hit& hit, int depth) {
  if (!hit.hit()) {
    add_escape(ctx, p, ray_of(ctx.buffers.rays, k), depth);
    return std::nullopt;
  }
  const Scene& scene = ctx.tracer.scene();
  uint32_t row = scene.material_of(hit.prim);
  if (scene.materials[row].is_light) {
    const Rayd ray = ray_of(ctx.buffers.rays, k);
    ensure_surface(ctx, ray, hit);
    add_emission(ctx, p, ray, hit, depth);
    return std::nullopt;
  }
  if (depth >= ctx.settings.max_depth) return std::nullopt;
  return row;
}

// The shadow ray toward a sampled light point, given the BSDF's f·|cos θi| and density there.
void queue_shadow_ray(TileContext& ctx, uint32_t path, const PathState& p, const Rayd& ray,
                      const Hit& hit, const LightSample& ls, const Vec3d& f, double bsdf_pdf) {
  Vec3d c;
  if (!shadow_contribution(vertex_rules(ctx, 0), p.beta, f, ls.le, ls.pdf, bsdf_pdf, c)) return;
  Vec3d o = offset_ray_origin(hit.surface.p, hit_point_error(ray, hit.t), hit.surface.ng, ls.wi);
  RayAppender(ctx.buffers.shadow_rays, 1, true)
      .push(ray_cast<float>(Rayd{o, ls.wi, 0, shadow_ray_tmax(o, hit.surface.p, ls.wi, ls.dist)}),
            ls.light.bits());
  ctx.buffers.next_queries.push_back(path, c);
}

// After the BSDF's sample: the throughput, Russian roulette, the next ray (into `next`).
// False when the path ends here.
bool continue_path(PathState& p, const Rayd& ray, const Hit& hit, const BsdfSample& s,
                   double u_roulette, const VertexRules& rules, Rayd& next) {
  if (!next_throughput(rules, p.beta, s.value, s.pdf, u_roulette, p.beta)) return false;
  p.prev_p = hit.surface.p;
  p.prev_pdf = s.pdf;
  p.prev_specular = s.specular;
  Vec3d o = offset_ray_origin(hit.surface.p, hit_point_error(ray, hit.t), hit.surface.ng, s.wi);
  next = {o, s.wi};
  return true;
}

// One vertex with the double Bsdf: light sampling, then the next direction.
bool shade_vertex_double(TileContext& ctx, uint32_t path, PathState& p, const Rayd& ray,
                         const Hit& hit, const Material& material, int depth, Rayd& next) {
  // A textured Kd: the material with Kd times the image at the hit (lobe choice follows it).
  Material m = material;
  if (m.texture >= 0)
    m.kd = Vec3f(Vec3d(m.kd) * texture_factor(ctx.tracer.scene(), m, hit.prim, hit.surface));
  Bsdf bsdf(m, hit.surface.ns, -ray.d);
  if (bsdf.black()) return false;
  if (samples_lights(ctx)) {
    LightSample ls = sample_light_point(ctx, p, hit, depth);
    if (ls.valid()) {
      BsdfEval e = bsdf.evaluate(ls.wi);
      queue_shadow_ray(ctx, path, p, ray, hit, ls, e.f, e.pdf);
    }
  }
  auto u = draw(ctx, p, Dims::bsdf(depth), {2, 0, 1});
  BsdfSample s = bsdf.sample(u[2], u[0], u[1]);
  if (!s.valid()) return false;
  double u_roulette = depth + 1 >= ctx.settings.rr_depth ? roulette_uniform(ctx, u) : 0.0;
  return continue_path(p, ray, hit, s, u_roulette, vertex_rules(ctx, depth), next);
}

}  // namespace

// The course: exp(t·ln Kt) per channel, applied to the segment that ends on the inside of a
// surface. A material with Kt = 0 has no interior.
Vec3d beer(const Material& m, bool front_face, double t) {
  Vec3d kt(m.kt);
  if (front_face || kt == Vec3d(0, 0, 0)) return {1, 1, 1};
  Vec3d a;
  for (int k = 0; k < 3; ++k)
    a[k] = kt[k] > 0 ? std::exp(t * std::log(kt[k])) : 0.0;
  return a;
}

bool samples_lights(const TileContext& ctx) {
  return ctx.settings.integrator != Integrator::kBrdf && !ctx.lights.empty();
}

VertexRules vertex_rules(const TileContext& ctx, int depth) {
  return {ctx.settings.integrator == Integrator::kMis, depth + 1 >= ctx.settings.rr_depth,
          kRouletteSurvival};
}

void shade_wavefront(TileContext& ctx, int depth) {
  ThreadBuffers& b = ctx.buffers;
  const bool lanes = ctx.settings.shading == Shading::kFloat;
  b.lane_count = 0;
  if (lanes) start_lane_rows(ctx, b.live.size());
  for (std::size_t k = 0; k < b.live.size(); ++k) {
    uint32_t path = b.live[k];
    PathState& p = b.paths[path];
    Hit& hit = b.hits[k];
    std::optional<uint32_t> material = arrive(ctx, p, k, hit, depth);
    if (!material) continue;
    if (lanes && ctx.lanes.materials.in_lanes[*material]) {
      queue_lane_row(ctx, path, uint32_t(k), *material);
      continue;
    }
    const Rayd ray = ray_of(b.rays, k);
    const Material& m = ctx.tracer.scene().materials[*material];
    ensure_surface(ctx, ray, hit);
    p.beta = p.beta * beer(m, hit.front_face, hit.t);
    Rayd next;
    if (!shade_vertex_double(ctx, path, p, ray, hit, m, depth, next)) continue;
    b.next_live.push_back(path);
    RayAppender(b.next_rays, 1, false).push(ray_cast<float>(next));
  }
  if (b.lane_count > 0) shade_in_lanes(ctx, depth);
}

}  // namespace raylane::path_detail
