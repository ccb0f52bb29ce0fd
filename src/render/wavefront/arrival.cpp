// The stage after tracing: the shadow rays' answers, and where each ray arrived — the
// environment for an escaped ray, the emission of an emitter it hit (both finish the path
// here), or a queue of vertices to shade.
#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <span>

#include "raylane/render/arrival_lanes.h"
#include "raylane/render/vertex_steps.h"
#include "render/wavefront/stages.h"

namespace raylane::path_detail {

namespace {

// Light sampling's weight for what a path meets at the end of a ray: all of it for a camera ray,
// for BSDF sampling alone or after a specular bounce (light sampling cannot reach a Dirac lobe);
// the MIS share after another bounce, nothing for NEE alone (light sampling counted it
// already). `light_pdf` is called only for the MIS share.
template <class LightPdf>
double emission_weight(const ThreadContext& ctx, const Carried& p, LightPdf light_pdf) {
  bool sampled_light_too = p.depth > 0 && !p.prev_specular;
  if (!sampled_light_too || ctx.settings.integrator == Integrator::kBrdf) return 1;
  if (ctx.settings.integrator == Integrator::kNee) return 0;
  return power_heuristic(p.prev_pdf, light_pdf());
}

// What a path gains where its ray, carrying p, hits an emitter (its density for MIS is the
// light sampler's).
void add_emission(ThreadContext& ctx, PathState& path, const Carried& p, const Rayd& ray,
                  const Hit& hit) {
  glm::dvec3 le = ctx.lights.emitted(hit);
  if (le == glm::dvec3(0, 0, 0)) return;
  double w = emission_weight(ctx, p, [&] {
    return ctx.lights.pdf(glm::dvec3(p.prev_p), ray.d, hit,
                          ray.time);  // a moving light's at the ray's time
  });
  path.radiance += p.beta * le * w;
}

// What the paths gain whose rays left the scene (w.escaped): the environment, looked up for all
// of them at once (its density for MIS is the environment's).
void add_escapes(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  if (w.escaped.empty()) return;
  EnvironmentSeenBatch& b = w.escapes;
  b.dir.resize(w.escaped.size());
  for (std::size_t i = 0; i < w.escaped.size(); ++i)
    b.dir[i] = ray_of(w.rays.rays, w.escaped[i]).d;
  ctx.lights.escaped_many(b);
  for (std::size_t i = 0; i < w.escaped.size(); ++i) {
    const EnvironmentMap::Seen& seen = b.seen[i];
    if (seen.le == glm::dvec3(0, 0, 0)) continue;
    const Carried p = w.rays.carry.get(w.escaped[i]);
    double weight = emission_weight(ctx, p, [&] { return seen.pdf; });
    w.paths[w.rays.path[w.escaped[i]]].radiance += p.beta * seen.le * weight;
  }
}

// Each primitive kind's material column, taken once per wavefront: a hit's material is then
// one load (Scene::material_of dispatches on the kind at every call).
class MaterialColumns {
 public:
  explicit MaterialColumns(const Scene& scene) {
    PrimKinds::for_each([&](auto kind) {
      using Kind = decltype(kind);
      of_[kind_index<Kind>()] = scene.table<Kind>().material.data();
    });
  }
  uint32_t operator()(PrimRef prim) const { return of_[std::size_t(prim.tag())][prim.row()]; }

 private:
  std::array<const uint32_t*, kPrimKindCount> of_{};
};

}  // namespace

// Without a branch per ray: whether a shadow ray is blocked is a coin the predictor cannot
// learn (the branches saved: bench/README.md, "The surfaces' rows read in place, ..."). A
// blocked ray adds +0, which leaves the sum's bits as they were (the radiance starts at +0
// and adds no −0 sums);
// the select, not a product by 0, keeps a blocked ray's contribution out even where it is not
// finite.
void add_unblocked_shadows(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  const ShadowQueue& s = w.shadows;
  const uint8_t* blocked = w.blocked.data();
  const uint32_t* path = s.path.data();
  const double* c[3] = {s.contribution[0].data(), s.contribution[1].data(),
                        s.contribution[2].data()};
  PathState* paths = w.paths.data();
  for (std::size_t q = 0; q < s.size(); ++q) {
    // All ones where the ray is open: a select by a mask, which GCC keeps as one (a ?: on
    // doubles it turned back into the branch).
    const uint64_t open = uint64_t(0) - uint64_t(blocked[q] == 0);
    glm::dvec3& radiance = paths[path[q]].radiance;
    for (int k = 0; k < 3; ++k)
      radiance[k] += std::bit_cast<double>(std::bit_cast<uint64_t>(c[k][q]) & open);
  }
}

namespace {

// The arrivals the lanes leave to scalar code, in ray order: an escape under an environment,
// an emitter (both end the path), a vertex shaded in double.
void finish_rare_arrivals(ThreadContext& ctx, const MaterialColumns& material_of,
                          std::span<const uint32_t> rare) {
  Wavefront& w = ctx.wave;
  const LaneMaterials::Route* route = ctx.lanes.materials.route.data();
  for (const uint32_t k : rare) {
    const PrimRef hit = PrimRef::from_bits(w.hits.prim[k]);
    if (!hit.valid()) {
      w.escaped.push_back(k);
      continue;
    }
    const uint32_t material = material_of(hit);
    if (route[material] == LaneMaterials::Route::kEmitter) {  // emitters reflect nothing
      const Rayd ray = ray_of(w.rays.rays, k);
      add_emission(ctx, w.paths[w.rays.path[k]], w.rays.carry.get(k), ray,
                   w.record(k, ctx.tracer, ray));
      continue;
    }
    w.double_vertices.push(k, material);
  }
}

}  // namespace

void sort_arrivals(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  const Scene& scene = ctx.tracer.scene();
  const std::size_t n = w.rays.size();
  using Route = LaneMaterials::Route;
  // The route of the materials shaded in lanes; none with the double shading.
  const bool lanes = ctx.settings.shading == Shading::kFloat;
  const PathCarry& carry = w.rays.carry;
  ArrivalColumns in;
  in.prim = w.hits.prim.data(), in.ray_path = w.rays.path.data(), in.count = n;
  in.depth = carry.depth.data();
  in.beta = {carry.beta[0].data(), carry.beta[1].data(), carry.beta[2].data()};
  set_material_columns(scene, in);
  in.route = reinterpret_cast<const uint32_t*>(ctx.lanes.materials.route.data());
  in.materials = ctx.lanes.materials.route.size();
  in.emitter_route = uint32_t(Route::kEmitter);
  in.lanes_route = uint32_t(lanes ? Route::kLanes : Route::kNone);
  in.max_depth = uint32_t(std::max(ctx.settings.max_depth, 0));
  // Without an environment an escaped ray adds nothing (add_escapes would find 0).
  in.environment = ctx.lights.environment() != nullptr;
  // The lane rows' Sobol seeds (LaneVertexQueue::light_seed, bsdf_seed: the path's pixel seed
  // salted by the groups of the row's depth, Dims) and roulette's survival
  // (VertexBatch::survival, has_roulette's rows).
  static_assert(sizeof(PathState) % sizeof(uint64_t) == 0 && offsetof(PathState, pixel_seed) == 0,
                "the seeds' stride in words");
  in.pixel_seed = &w.paths.data()->pixel_seed;
  in.seed_stride = uint32_t(sizeof(PathState) / sizeof(uint64_t));
  in.light_salt = group_salt(Dims::light_group(0));
  in.salt_step = group_salt(Dims::light_group(1)) - in.light_salt;
  in.bsdf_offset = group_salt(Dims::bsdf_group(0)) - in.light_salt;
  in.roulette_from = uint32_t(std::max(ctx.settings.rr_depth - 1, 0));
  in.survival = float(kRouletteSurvival);
  w.double_vertices.clear();
  w.escaped.clear();
  w.rare_arrivals.resize((n + 15) / 16 * 16);
  if (lanes) start_lane_vertices(ctx, n);
  LaneVertexQueue& lv = w.lane_vertices;
  ArrivalRows out;
  out.path = lv.path.data(), out.ray = lv.ray.data(), out.material = lv.material.data();
  out.depth = lv.depth.data(), out.rare = w.rare_arrivals.data();
  out.light_seed = lv.light_seed.data(), out.bsdf_seed = lv.bsdf_seed.data();
  out.survival = lv.vertices.survival.data();
  VertexBatch& vb = lv.vertices;
  out.beta = {vb.beta[0].data(), vb.beta[1].data(), vb.beta[2].data()};
  ctx.lanes.kernels.sort_arrivals(in, out);
  lv.any_roulette = out.any_roulette;
  lv.count = out.lanes;
  finish_rare_arrivals(ctx, MaterialColumns(scene),
                       std::span<const uint32_t>(w.rare_arrivals.data(), out.rare_count));
  add_escapes(ctx);
}

}  // namespace raylane::path_detail
