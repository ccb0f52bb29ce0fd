// The stage that shades the double_vertices queue one vertex at a time with the double Bsdf
// (materials the lanes do not take, and every vertex with Shading::kDouble): light sampling
// and its shadow ray, the BSDF's sample, roulette and the next ray.
#include <algorithm>
#include <vector>

#include "raylane/core/ray_offset.h"
#include "raylane/render/materials/bsdf.h"
#include "raylane/render/materials/texturing.h"
#include "render/wavefront/stages.h"

namespace raylane::path_detail {

namespace {

// Roulette's number: the BSDF group's last component, drawn from MT19937 only when needed.
double roulette_uniform(ThreadContext& ctx, const std::array<double, 4>& bsdf_group) {
  return ctx.settings.sampler == Sampler::kSobol ? bsdf_group[3] : ctx.rng.uniform();
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

// Next-event estimation's point on a light, seen from this vertex (invalid: none).
LightSample sample_light_point(ThreadContext& ctx, const PathState& p, const Rayd& ray,
                               const Hit& hit, uint32_t depth) {
  const auto u = draw(ctx, p, Dims::light_group(depth), kLightDrawOrder);
  bool timed = ctx.settings.time_phases && ctx.light_calls++ % kLightTimingStride == 0;
  PhaseClock clock(timed);
  LightSample ls = ctx.lights.sample(hit.surface.p, u[2], u[3], u[0], u[1], ray.time);
  if (timed) {
    double t = 0;
    clock.lap(t);
    ctx.stats.phases.lights += std::max(0.0, t - clock_read_seconds()) * kLightTimingStride;
  }
  return ls;
}

// The shadow ray toward a sampled light point, given the BSDF's f·|cos θi| and density there.
void queue_shadow_ray(ThreadContext& ctx, uint32_t path, const glm::dvec3& beta, const Rayd& ray,
                      const Hit& hit, const LightSample& ls, const glm::dvec3& f, double bsdf_pdf) {
  glm::dvec3 c{};
  if (!shadow_contribution(vertex_rules(ctx, 0), beta, f, ls.le, ls.pdf, bsdf_pdf, c)) return;
  glm::dvec3 o =
      offset_ray_origin(hit.surface.p, ctx.tracer.hit_point_bound(ray, hit), hit.surface.ng, ls.wi);
  ShadowQueue& s = ctx.wave.next_shadows;
  RayAppender(s.rays, 1, true)
      .push(ray_cast<float>(Rayd{o, ls.wi, 0, shadow_ray_tmax(o, hit.surface.p, ls.wi, ls.dist)}),
            ls.light.bits());
  s.push_back(path, c);
}

// After the BSDF's sample: the throughput, Russian roulette, the next ray (into `next`) and
// what it carries (into `p`, from the vertex's). False when the path ends here.
bool continue_path(const Tracer& tracer, Carried& p, const Rayd& ray, const Hit& hit,
                   const BsdfSample& s, double u_roulette, const VertexRules& rules, Rayd& next) {
  if (!next_throughput(rules, p.beta, s.value, s.pdf, u_roulette, p.beta)) return false;
  p.prev_p = glm::vec3(hit.surface.p);
  p.prev_pdf = s.pdf;
  p.prev_specular = s.specular;
  ++p.depth;
  glm::dvec3 o =
      offset_ray_origin(hit.surface.p, tracer.hit_point_bound(ray, hit), hit.surface.ng, s.wi);
  next = {o, s.wi};
  return true;
}

// One vertex with the double Bsdf, its ray carrying c: light sampling, then the next direction
// (c then what the next ray carries).
bool shade_vertex_double(ThreadContext& ctx, uint32_t path, const PathState& p, Carried& c,
                         const Rayd& ray, const Hit& hit, const Material& material, Rayd& next) {
  const uint32_t depth = c.depth;
  // A textured Kd: the material with Kd times the image at the hit (lobe choice follows it).
  Material m = material;
  if (m.texture >= 0)
    m.kd =
        glm::vec3(glm::dvec3(m.kd) * texture_factor(ctx.tracer.scene(), m, hit.prim, hit.surface));
  Bsdf bsdf(m, hit.surface.ns, -ray.d);
  if (bsdf.black()) return false;
  if (samples_lights(ctx)) {
    LightSample ls = sample_light_point(ctx, p, ray, hit, depth);
    if (ls.valid()) {
      BsdfEval e = bsdf.evaluate(ls.wi);
      queue_shadow_ray(ctx, path, c.beta, ray, hit, ls, e.f, e.pdf);
    }
  }
  auto u = draw(ctx, p, Dims::bsdf_group(depth), kBsdfDrawOrder);
  BsdfSample s = bsdf.sample(u[2], u[0], u[1]);
  if (!s.valid()) return false;
  const VertexRules rules = vertex_rules(ctx, depth);
  double u_roulette = rules.roulette ? roulette_uniform(ctx, u) : 0.0;
  return continue_path(ctx.tracer, c, ray, hit, s, u_roulette, rules, next);
}

}  // namespace

void shade_double_vertices(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  const DoubleVertexQueue& q = w.double_vertices;
  const std::vector<Material>& materials = ctx.tracer.scene().materials;
  for (std::size_t i = 0; i < q.ray.size(); ++i) {
    const uint32_t k = q.ray[i], path = w.rays.path[k];
    const Rayd ray = ray_of(w.rays.rays, k);
    const Hit hit = w.record(k, ctx.tracer, ray);
    const Material& m = materials[q.material[i]];
    Carried c = w.rays.carry.get(k);
    c.beta = c.beta * beer_transmittance(m, hit.front_face, hit.t);
    Rayd next;
    if (!shade_vertex_double(ctx, path, w.paths[path], c, ray, hit, m, next)) continue;
    w.next_rays.push(path, ray_cast<float>(next), c);
  }
}

}  // namespace raylane::path_detail
