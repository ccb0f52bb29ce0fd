// The stage after tracing: the shadow rays' answers, and where each ray arrived — the
// environment for an escaped ray, the emission of an emitter it hit (both finish the path
// here), or a queue of vertices to shade.
#include <algorithm>
#include <array>

#include "raylane/render/vertex_steps.h"
#include "render/wavefront/stages.h"

namespace raylane::path_detail {

namespace {

// Light sampling's weight for what a path meets at the end of a ray: all of it for a camera ray,
// for BSDF sampling alone or after a specular bounce (light sampling cannot reach a Dirac lobe);
// the MIS share after another bounce, nothing for NEE alone (light sampling counted it
// already). `light_pdf` is called only for the MIS share.
template <class LightPdf>
double emission_weight(const ThreadContext& ctx, const PathState& p, LightPdf light_pdf) {
  bool sampled_light_too = p.depth > 0 && !p.prev_specular;
  if (!sampled_light_too || ctx.settings.integrator == Integrator::kBrdf) return 1;
  if (ctx.settings.integrator == Integrator::kNee) return 0;
  return power_heuristic(p.prev_pdf, light_pdf());
}

// What a path gains where it hits an emitter (its density for MIS is the light sampler's).
void add_emission(ThreadContext& ctx, PathState& p, const Rayd& ray, const Hit& hit) {
  glm::dvec3 le = ctx.lights.emitted(hit);
  if (le == glm::dvec3(0, 0, 0)) return;
  double w = emission_weight(ctx, p, [&] {
    return ctx.lights.pdf(glm::dvec3(p.prev_p), ray.d, hit,
                          ray.time);  // a moving light's at the ray's time
  });
  p.radiance += p.beta * le * w;
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
    PathState& p = w.paths[w.rays.path[w.escaped[i]]];
    double weight = emission_weight(ctx, p, [&] { return seen.pdf; });
    p.radiance += p.beta * seen.le * weight;
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

void add_unblocked_shadows(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  const ShadowQueue& s = w.shadows;
  for (std::size_t q = 0; q < s.size(); ++q)
    if (w.blocked[q] == 0) w.paths[s.path[q]].radiance += s.contribution_of(q);
}

namespace {

// The lane_vertices rows sort_arrivals appends, with the path's throughput for the scatter
// kernel, read while the path is at hand (a pass of its own gathered it again from the paths
// scattered in memory). Their columns' pointers and the count are held in locals
// through the loop (stores through the queue's vectors could alias its count and pointers, so
// the compiler reloaded them at every row).
struct LaneRowWriter {
  uint32_t *path, *ray, *material, *depth;
  uint64_t* pixel_seed;
  float *beta_x, *beta_y, *beta_z;
  std::size_t count;
  explicit LaneRowWriter(LaneVertexQueue& q)
      : path(q.path.data()),
        ray(q.ray.data()),
        material(q.material.data()),
        depth(q.depth.data()),
        pixel_seed(q.pixel_seed.data()),
        beta_x(q.vertices.beta[0].data()),
        beta_y(q.vertices.beta[1].data()),
        beta_z(q.vertices.beta[2].data()),
        count(q.count) {}
  void push(uint32_t p, uint32_t k, uint32_t m, uint32_t d, const PathState& state) {
    const std::size_t r = count++;
    path[r] = p, ray[r] = k, material[r] = m, depth[r] = d;
    pixel_seed[r] = state.pixel_seed;
    // Beer's law on a back face follows with the surfaces (lane_vertices.cpp, path_columns).
    beta_x[r] = float(state.beta.x), beta_y[r] = float(state.beta.y);
    beta_z[r] = float(state.beta.z);
  }
};

}  // namespace

namespace {

// The arrivals that leave the lane rows' loop, out of line (noinline): inlined, their vector
// growth and the emission's double work kept the loop's pointers from registers, and every
// lane row reloaded them.
[[gnu::noinline]] void arrive_at_emitter(ThreadContext& ctx, PathState& p, std::size_t k) {
  const Rayd ray = ray_of(ctx.wave.rays.rays, k);
  add_emission(ctx, p, ray, ctx.wave.record(k, ctx.tracer, ray));
}
[[gnu::noinline]] void queue_double_vertex(Wavefront& w, uint32_t k, uint32_t material,
                                           uint32_t depth) {
  w.double_vertices.push(k, material, depth);
}
[[gnu::noinline]] void queue_escape(Wavefront& w, uint32_t k) {
  w.escaped.push_back(k);
}

}  // namespace

void sort_arrivals(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  const Scene& scene = ctx.tracer.scene();
  const MaterialColumns material_of(scene);
  const LaneMaterials::Route* route = ctx.lanes.materials.route.data();
  // The route of the materials shaded in lanes; none with the double shading.
  const bool lanes = ctx.settings.shading == Shading::kFloat;
  const auto to_lanes = lanes ? LaneMaterials::Route::kLanes : LaneMaterials::Route::kNone;
  // Without an environment an escaped ray adds nothing (add_escapes would find 0).
  const bool environment = ctx.lights.environment() != nullptr;
  const uint32_t max_depth = uint32_t(std::max(ctx.settings.max_depth, 0));
  w.double_vertices.clear();
  w.escaped.clear();
  if (lanes) start_lane_vertices(ctx, w.rays.size());
  LaneRowWriter lane_rows(w.lane_vertices);
  const uint32_t* prim = w.hits.prim.data();
  const uint32_t* ray_path = w.rays.path.data();
  PathState* paths = w.paths.data();
  const std::size_t n = w.rays.size();
  for (std::size_t k = 0; k < n; ++k) {
    const uint32_t path = ray_path[k];
    PathState& p = paths[path];
    const PrimRef hit = PrimRef::from_bits(prim[k]);
    if (!hit.valid()) {
      if (environment) queue_escape(w, uint32_t(k));
      continue;
    }
    const uint32_t material = material_of(hit);
    const LaneMaterials::Route to = route[material];
    if (to == LaneMaterials::Route::kEmitter) {  // emitters reflect nothing: the path ends
      arrive_at_emitter(ctx, p, k);
      continue;
    }
    const uint32_t depth = p.depth;
    if (depth >= max_depth) continue;
    p.depth = depth + 1;  // where the ray it sends on (if any) arrives
    if (to == to_lanes)
      lane_rows.push(path, uint32_t(k), material, depth, p);
    else
      queue_double_vertex(w, uint32_t(k), material, depth);
  }
  w.lane_vertices.count = lane_rows.count;
  add_escapes(ctx);
}

}  // namespace raylane::path_detail
