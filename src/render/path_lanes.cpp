// A wavefront's vertices shaded at once: their numbers (Sobol groups in lanes), their light
// points (render/lights.h, sample_many), their BSDFs in float lanes (render/shade_lanes.h),
// then each vertex's shadow ray and next ray (render/path_loop.h).
#include <cmath>

#include "render/path_loop.h"

namespace raylane::path_detail {

namespace {

// The queued vertices' light points, all at once (sphere lights in lanes), from the numbers
// already in light_queries.u; row r's is light_queries.out[r] (light_of).
void sample_lights_in_lanes(TileContext& ctx) {
  ThreadBuffers& b = ctx.buffers;
  PhaseClock clock(ctx.settings.time_phases);
  LightQueries& q = b.light_queries;
  for (std::size_t r = 0; r < b.lane_count; ++r)
    q.ref[r] = b.hits[b.lane_rows[r].hit].surface.p;
  ctx.lights.sample_many(ctx.lanes.isa, q);
  clock.lap(ctx.stats.phases.lights);
}

// The numbers of one Sobol group for every queued vertex, from the lanes.
template <class Store>
void sobol_for_rows(TileContext& ctx, uint32_t group, Store store) {
  SobolBatch& sb = ctx.buffers.sobol;
  sobol_groups(ctx.lanes.isa, ctx.pass, group, sb);
  for (std::size_t r = 0; r < ctx.buffers.lane_count; ++r)
    store(r, ctx.buffers.lane_rows[r],
          std::array<double, 4>{sb.u[0][r] * 0x1p-32, sb.u[1][r] * 0x1p-32, sb.u[2][r] * 0x1p-32,
                                sb.u[3][r] * 0x1p-32});
}

// The queued vertices' numbers — Sobol groups for all of them at once in lanes, or MT19937
// row by row in the double shading's order (light, BSDF, roulette) — then their light points.
void draw_lane_rows(TileContext& ctx, int depth) {
  ThreadBuffers& b = ctx.buffers;
  const bool lights = samples_lights(ctx), roulette = depth + 1 >= ctx.settings.rr_depth;
  b.lights_sampled = lights;
  if (lights) b.light_queries.resize(b.lane_count);
  if (ctx.settings.sampler == Sampler::kSobol) {
    b.sobol.resize(b.lane_count);
    for (std::size_t r = 0; r < b.lane_count; ++r)
      b.sobol.seed[r] = b.paths[b.lane_rows[r].path].pixel_seed;
    if (lights)
      sobol_for_rows(ctx, Dims::light(depth),
                     [&b](std::size_t r, LaneRow&, auto u) { b.light_queries.u[r] = u; });
    sobol_for_rows(ctx, Dims::bsdf(depth), [](std::size_t, LaneRow& row, auto u) {
      row.u = u;
      row.u_roulette = u[3];
    });
  } else {
    for (std::size_t r = 0; r < b.lane_count; ++r) {
      LaneRow& row = b.lane_rows[r];
      const PathState& p = b.paths[row.path];
      if (lights) b.light_queries.u[r] = draw(ctx, p, Dims::light(depth), {2, 3, 0, 1});
      row.u = draw(ctx, p, Dims::bsdf(depth), {2, 0, 1});
      if (roulette) row.u_roulette = ctx.rng.uniform();
    }
  }
  if (lights) sample_lights_in_lanes(ctx);
}

// After the BSDF: each vertex's shadow ray and next ray, in double lanes (render/vertex_lanes.h,
// queue_shadow_ray's and continue_path's steps bit for bit), then queued and written back.
void finish_in_lanes(TileContext& ctx, int depth) {
  ThreadBuffers& b = ctx.buffers;
  const ShadeBatch& sb = b.shade;
  VertexBatch& vb = b.vertices;
  vb.resize(b.lane_count);
  const VertexRules rules = vertex_rules(ctx, depth);
  for (std::size_t r = 0; r < b.lane_count; ++r) {
    const LaneRow& row = b.lane_rows[r];
    const PathState& p = b.paths[row.path];
    const Hit& hit = b.hits[row.hit];
    const LightSample& light = light_of(b, r);
    const bool lit = light.valid();
    for (int k = 0; k < 3; ++k) {
      vb.beta[k][r] = p.beta[k], vb.p[k][r] = hit.surface.p[k], vb.ng[k][r] = hit.surface.ng[k];
      vb.ray_o[k][r] = p.ray.o[k], vb.ray_d[k][r] = p.ray.d[k];
      vb.light_wi[k][r] = lit ? light.wi[k] : 0.0;
      vb.light_le[k][r] = lit ? light.le[k] : 0.0;
      vb.light_f[k][r] = sb.light_f[k][r];
      vb.wi[k][r] = sb.wi[k][r], vb.value[k][r] = sb.value[k][r];
    }
    vb.t[r] = hit.t;
    vb.light_pdf[r] = lit ? light.pdf : 0.0, vb.light_bsdf_pdf[r] = sb.light_pdf[r];
    vb.pdf[r] = sb.pdf[r], vb.u_roulette[r] = rules.roulette ? row.u_roulette : 0.0;
  }
  finish_vertices(ctx.lanes.isa, rules, vb);
  for (std::size_t r = 0; r < b.lane_count; ++r) {
    const LaneRow& row = b.lane_rows[r];
    auto column3 = [r](const VertexBatch::Columns3& c) { return Vec3d(c[0][r], c[1][r], c[2][r]); };
    if (vb.shadow_ok[r] != 0) {
      const LightSample& light = light_of(b, r);
      b.shadow_rays.push_back({column3(vb.shadow_o), light.wi});
      b.next_queries.push_back({row.path, light.light, column3(vb.shadow_c)});
    }
    if (vb.alive[r] == 0) continue;
    PathState& p = b.paths[row.path];
    p.beta = column3(vb.next_beta);
    p.prev_p = b.hits[row.hit].surface.p;
    p.prev_pdf = vb.pdf[r];
    p.prev_specular = false;
    p.ray = {column3(vb.next_o), column3(vb.wi)};
    b.next_live.push_back(row.path);
  }
}

}  // namespace

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
}

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
    const LightSample& light = light_of(b, r);
    const Vec3d light_wi = light.valid() ? light.wi : Vec3d(0, 0, 0);
    for (int k = 0; k < 3; ++k) {
      sb.n[k][r] = float(hit.surface.ns[k]);
      sb.wo[k][r] = float(wo[k]);
      sb.light_wi[k][r] = float(light_wi[k]);
    }
    sb.u_lobe[r] = float(row.u[2]), sb.u1[r] = float(row.u[0]), sb.u2[r] = float(row.u[1]);
  }
  shade_lanes(ctx.lanes.isa, ctx.lanes.materials, sb);
  finish_in_lanes(ctx, depth);
}

}  // namespace raylane::path_detail
