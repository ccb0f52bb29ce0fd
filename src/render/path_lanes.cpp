// A wavefront's vertices shaded at once, in columns: queue_lane_row lists each vertex as the
// wavefront arrives; the tracer writes their surfaces straight into the batches' columns, and
// a few passes copy the listed hits, rays and paths into the rest, a column group per pass (a
// pass over all thirty columns at once reloaded each column's pointer per row); then the rows'
// numbers (Sobol groups in lanes), light points (render/lights.h, sample_many), BSDFs in float
// lanes (render/shade_lanes.h) and shadow rays and next rays in double lanes
// (render/vertex_lanes.h, reading the light points and BSDF answers where those steps left
// them) all read and write columns; last passes write the rays and the paths back. (Each step
// once gathered what it needed from the hits and paths itself: seven passes over the rows, 18 %
// of a render.)
#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "raylane/core/ray_offset.h"
#include "render/path_loop.h"

namespace raylane::path_detail {

namespace {

// The BSDF group's numbers for row r: (u1, u2, lobe) for the float lanes, roulette's for the
// double ones (0 where this depth has no roulette).
void set_bsdf_numbers(TileContext& ctx, std::size_t r, const std::array<double, 4>& u,
                      double u_roulette) {
  ShadeBatch& sb = ctx.buffers.shade;
  sb.u1[r] = unit_float(u[0]), sb.u2[r] = unit_float(u[1]), sb.u_lobe[r] = unit_float(u[2]);
  ctx.buffers.vertices.u_roulette[r] = u_roulette;
}

// The light group's numbers for row r: (u1, u2, u_light, u_part).
void set_light_numbers(LightQueries& q, std::size_t r, const std::array<double, 4>& u) {
  q.cones.u1[r] = u[0], q.cones.u2[r] = u[1], q.u_light[r] = u[2], q.u_part[r] = u[3];
}

// The rows' numbers: Sobol groups for all of them at once in lanes, or MT19937 row by row in
// the double shading's order (light, BSDF, roulette).
void draw_numbers(TileContext& ctx, int depth, bool lights, bool roulette) {
  ThreadBuffers& b = ctx.buffers;
  LightQueries& q = b.light_queries;
  if (ctx.settings.sampler != Sampler::kSobol) {
    for (std::size_t r = 0; r < b.lane_count; ++r) {
      const PathState& p = b.paths[b.lane_rows.path[r]];
      if (lights) set_light_numbers(q, r, draw(ctx, p, Dims::light(depth), {2, 3, 0, 1}));
      auto u = draw(ctx, p, Dims::bsdf(depth), {2, 0, 1});
      set_bsdf_numbers(ctx, r, u, roulette ? ctx.rng.uniform() : 0.0);
    }
    return;
  }
  // Sobol: each group in lanes, its numbers written straight into the columns that read them.
  SobolBatch& s = b.sobol;
  if (lights) {  // only the numbers the lights read (for one sphere light, no table gathers)
    const int read = ctx.lights.numbers_read();
    SobolNumbers to;
    to.as_double = {q.cones.u1.data(), q.cones.u2.data(), read > 2 ? q.u_light.data() : nullptr,
                    read > 3 ? q.u_part.data() : nullptr};
    sobol_groups(ctx.lanes.isa, ctx.pass, Dims::light(depth), s, first_components(read), to);
  }
  // Roulette's number only at the depths that have roulette (the vertex lanes read it only
  // there).
  // The lobe's number only where a material has more than one lobe (else 0, which picks the
  // diffuse lobe as every number in [0, 1) would): for a diffuse-only scene below roulette's
  // depth, no table gathers at all.
  ShadeBatch& sb = b.shade;
  const bool lobe = !ctx.lanes.materials.lobe_unread;
  if (!lobe) std::fill_n(sb.u_lobe.begin(), b.lane_count, 0.0f);
  SobolNumbers to;
  to.as_float = {sb.u1.data(), sb.u2.data(), lobe ? sb.u_lobe.data() : nullptr, nullptr};
  if (roulette) to.as_double[3] = b.vertices.u_roulette.data();
  sobol_groups(ctx.lanes.isa, ctx.pass, Dims::bsdf(depth), s,
               3u | (lobe ? 4u : 0u) | (roulette ? 8u : 0u), to);
}

// The rows' light points (sphere lights in lanes): the float direction the BSDF is evaluated
// toward (0 for none, and for every row without lights). The vertex lanes read the rest where
// sample_many left it.
void light_columns(TileContext& ctx, bool lights) {
  ThreadBuffers& b = ctx.buffers;
  ShadeBatch& sb = b.shade;
  const std::size_t n = b.lane_count;
  if (!lights) {
    for (int k = 0; k < 3; ++k)
      std::fill_n(sb.light_wi[k].begin(), n, 0.0f);
    return;
  }
  PhaseClock clock(ctx.settings.time_phases);
  ctx.lights.sample_many(ctx.lanes.isa, b.light_queries);
  clock.lap(ctx.stats.phases.lights);
  const LightQueries& q = b.light_queries;
  const double* pdf = q.cones.pdf.data();
  for (int k = 0; k < 3; ++k) {
    const double* wi = q.cones.wi[std::size_t(k)].data();
    float* to = sb.light_wi[std::size_t(k)].data();
    for (std::size_t r = 0; r < n; ++r)
      to[r] = pdf[r] > 0 ? float(wi[r]) : 0.0f;  // LightQueries::valid
  }
}

// The three columns of c as pointers, taken once per pass: the passes below read a dozen
// columns per row, more than the registers that would keep the vectors' own pointers.
template <class T>
struct Column3View {
  const T *x, *y, *z;
  explicit Column3View(const std::array<std::vector<T>, 3>& c)
      : x(c[0].data()), y(c[1].data()), z(c[2].data()) {}
  Vec3<T> operator[](std::size_t r) const { return {x[r], y[r], z[r]}; }
};

// Room for `rows` more rows at the end of a stream (trimmed by the caller to what was kept).
std::size_t grow_stream(RayStream& s, std::size_t rows, bool aimed) {
  const std::size_t at = s.size();
  s.resize(at + rows);
  if (aimed) s.end.resize(at + rows);
  return at;
}

// The vertex lanes' shadow rays queued, each aimed at its light: the origin and end as the
// lanes rounded them, the direction as the BSDF was evaluated toward it (the light point's,
// rounded to float), and each one's query. A filter over the rows, in lanes.
void write_shadow_rays(TileContext& ctx) {
  ThreadBuffers& b = ctx.buffers;
  const VertexBatch& vb = b.vertices;
  const std::size_t n = b.lane_count;
  RayStream& s = b.shadow_rays;
  ShadowQueries& q = b.next_queries;
  const std::size_t at = grow_stream(s, n, true), queued = q.size();
  q.resize(queued + n);
  static_assert(sizeof(PrimRef) == 4 && std::is_trivially_copyable_v<PrimRef>,
                "a light's PrimRef is its 32 bits");
  RowFilter f;
  f.keep = vb.shadow_ok.data();
  f.add(vb.shadow_o[0].data(), s.ox.data() + at);
  f.add(vb.shadow_o[1].data(), s.oy.data() + at);
  f.add(vb.shadow_o[2].data(), s.oz.data() + at);
  f.add(b.shade.light_wi[0].data(), s.dx.data() + at);
  f.add(b.shade.light_wi[1].data(), s.dy.data() + at);
  f.add(b.shade.light_wi[2].data(), s.dz.data() + at);
  f.add(vb.shadow_tmax.data(), s.tmax.data() + at);
  f.add(reinterpret_cast<const uint32_t*>(b.light_queries.light.data()), s.end.data() + at);
  f.add(b.lane_rows.path.data(), q.path.data() + queued);
  for (std::size_t k = 0; k < 3; ++k)
    f.add(vb.shadow_c[k].data(), q.contribution[k].data() + queued);
  const std::size_t kept = filter_rows(ctx.lanes.isa, f, n);
  std::fill_n(s.tmin.begin() + std::ptrdiff_t(at), kept, 0.0f);
  s.resize(at + kept), s.end.resize(at + kept);
  q.resize(queued + kept);
}

// The vertex lanes' throughputs back to the paths (every row: a path that ends here is not
// read again, and the write spares a branch per row), then the next rays of the paths that go
// on and their list, filtered in lanes.
void write_next_rays(TileContext& ctx) {
  ThreadBuffers& b = ctx.buffers;
  const VertexBatch& vb = b.vertices;
  const std::size_t n = b.lane_count;
  const Column3View<double> beta(vb.next_beta), p(vb.p);
  const float* pdf = b.shade.pdf.data();
  const uint32_t* row_path = b.lane_rows.path.data();
  PathState* paths = b.paths.data();
  for (std::size_t r = 0; r < n; ++r) {
    PathState& path = paths[row_path[r]];
    path.beta = beta[r];
    path.prev_p = p[r];
    path.prev_pdf = pdf[r];
    path.prev_specular = false;
  }
  RayStream& s = b.next_rays;
  const std::size_t at = grow_stream(s, n, false), listed = b.next_live.size();
  b.next_live.resize(listed + n);
  RowFilter f;
  f.keep = vb.alive.data();
  for (std::size_t k = 0; k < 3; ++k)
    f.add(vb.next_o[k].data(), (k == 0 ? s.ox : k == 1 ? s.oy : s.oz).data() + at);
  for (std::size_t k = 0; k < 3; ++k)
    f.add(b.shade.wi[k].data(), (k == 0 ? s.dx : k == 1 ? s.dy : s.dz).data() + at);
  f.add(row_path, b.next_live.data() + listed);
  const std::size_t kept = filter_rows(ctx.lanes.isa, f, n);
  std::fill_n(s.tmin.begin() + std::ptrdiff_t(at), kept, 0.0f);
  std::fill_n(s.tmax.begin() + std::ptrdiff_t(at), kept, std::numeric_limits<float>::infinity());
  s.resize(at + kept);
  b.next_live.resize(listed + kept);
}

}  // namespace

void start_lane_rows(TileContext& ctx, std::size_t most) {
  ThreadBuffers& b = ctx.buffers;
  b.lane_count = 0;
  b.lane_rows.grow(most);
  b.shade.resize(most);
  b.vertices.resize(most);
  if (samples_lights(ctx)) b.light_queries.resize(most);
  if (ctx.settings.sampler == Sampler::kSobol) b.sobol.resize(most);
}

namespace {

// Three columns' pointers, taken once per pass.
template <class T>
struct Columns3Out {
  T *x, *y, *z;
  explicit Columns3Out(std::array<std::vector<T>, 3>& c)
      : x(c[0].data()), y(c[1].data()), z(c[2].data()) {}
  template <class V>
  void set(std::size_t r, const V& v) const {
    x[r] = T(v[0]), y[r] = T(v[1]), z[r] = T(v[2]);
  }
  // Row `from` into row `to`.
  void move(std::size_t to, std::size_t from) const {
    x[to] = x[from], y[to] = y[from], z[to] = z[from];
  }
};

// The queued rows' surfaces, straight into the batches' columns: the point and geometric
// normal (double) for the vertex lanes and the light sampler, the shading normal (float) for
// the BSDF; dot(ns, d) and the facing into the rows' own columns.
void surface_columns(TileContext& ctx) {
  ThreadBuffers& b = ctx.buffers;
  VertexBatch& vb = b.vertices;
  ShadeBatch& sb = b.shade;
  const SurfaceColumns out{vb.p[0].data(),          vb.p[1].data(),
                           vb.p[2].data(),          vb.ng[0].data(),
                           vb.ng[1].data(),         vb.ng[2].data(),
                           sb.n[0].data(),          sb.n[1].data(),
                           sb.n[2].data(),          b.lane_rows.cos_ns.data(),
                           b.lane_rows.front.data()};
  ctx.tracer.surfaces(b.rays, b.hits, {b.lane_rows.hit.data(), b.lane_count}, out, b.scratch);
}

// Whether row r's BSDF reflects something: a shading normal at a right angle to the ray, or not
// finite, or a material without lobes is Bsdf::black(), as the double shading decides it.
bool reflects(const LaneMaterials& lm, double cos_ns, uint32_t m) {
  return cos_ns != 0 && std::isfinite(cos_ns) && lm.pd[m] + lm.pr[m] + lm.pt[m] > 0;
}

// The queued rows whose BSDF reflects something, kept in order with their columns so far (the
// rest dropped). Seldom any to drop: one pass finds out, a second moves rows only then.
void drop_black_rows(TileContext& ctx) {
  ThreadBuffers& b = ctx.buffers;
  const LaneMaterials& lm = ctx.lanes.materials;
  LaneRows& rows = b.lane_rows;
  const std::size_t n = b.lane_count;
  std::size_t first = 0;
  while (first < n && reflects(lm, rows.cos_ns[first], rows.material[first]))
    ++first;
  if (first == n) return;
  const Columns3Out<double> p(b.vertices.p), ng(b.vertices.ng);
  const Columns3Out<float> ns(b.shade.n);
  std::size_t kept = first;
  for (std::size_t r = first + 1; r < n; ++r) {
    if (!reflects(lm, rows.cos_ns[r], rows.material[r])) continue;
    rows.path[kept] = rows.path[r], rows.hit[kept] = rows.hit[r];
    rows.material[kept] = rows.material[r], rows.front[kept] = rows.front[r];
    p.move(kept, r), ng.move(kept, r), ns.move(kept, r);
    ++kept;
  }
  b.lane_count = kept;
}

// The rows' t and material into the columns, and the point for the light sampler.
void hit_columns(TileContext& ctx, bool lights) {
  ThreadBuffers& b = ctx.buffers;
  const Hit* hits = b.hits.data();
  const uint32_t *hit = b.lane_rows.hit.data(), *material = b.lane_rows.material.data();
  const std::size_t n = b.lane_count;
  double* t = b.vertices.t.data();
  int32_t* shade_material = b.shade.material.data();
  for (std::size_t r = 0; r < n; ++r)
    t[r] = hits[hit[r]].t, shade_material[r] = int32_t(material[r]);
  if (!lights) return;
  for (int k = 0; k < 3; ++k)
    std::copy_n(b.vertices.p[k].begin(), n, b.light_queries.cones.ref[k].begin());
}

// The rows' rays (the stream's float rays, widened exactly), the paths' throughputs with
// Beer's law on the segment just travelled, and their scrambles into the columns.
void path_columns(TileContext& ctx, bool sobol) {
  ThreadBuffers& b = ctx.buffers;
  const LaneRows& rows = b.lane_rows;
  const std::size_t n = b.lane_count;
  const RayStream& rays = b.rays;
  const Columns3Out<double> ray_o(b.vertices.ray_o), ray_d(b.vertices.ray_d);
  const Columns3Out<float> wo(b.shade.wo);
  for (std::size_t r = 0; r < n; ++r) {
    const uint32_t i = rows.hit[r];
    const float dx = rays.dx[i], dy = rays.dy[i], dz = rays.dz[i];
    ray_o.set(r, std::array<float, 3>{rays.ox[i], rays.oy[i], rays.oz[i]});
    ray_d.set(r, std::array<float, 3>{dx, dy, dz});
    wo.set(r, std::array<float, 3>{-dx, -dy, -dz});
  }
  const PathState* paths = b.paths.data();
  const std::vector<Material>& materials = ctx.tracer.scene().materials;
  const Columns3Out<double> beta(b.vertices.beta);
  const double* t = b.vertices.t.data();
  uint64_t* seed = b.sobol.seed.data();
  for (std::size_t r = 0; r < n; ++r) {
    const PathState& path = paths[rows.path[r]];
    // Beer's law is 1 on a front face: no product there (x·1 = x, bit for bit).
    beta.set(
        r, rows.front[r] ? path.beta : path.beta * beer(materials[rows.material[r]], false, t[r]));
    if (sobol) seed[r] = path.pixel_seed;
  }
}

}  // namespace

void shade_in_lanes(TileContext& ctx, int depth) {
  ThreadBuffers& b = ctx.buffers;
  const bool lights = samples_lights(ctx), sobol = ctx.settings.sampler == Sampler::kSobol;
  const VertexRules rules = vertex_rules(ctx, depth);
  surface_columns(ctx);
  drop_black_rows(ctx);
  if (b.lane_count == 0) return;
  b.shade.resize(b.lane_count);  // these set the sizes and padding
  b.vertices.resize(b.lane_count);
  if (lights) b.light_queries.resize(b.lane_count);
  if (sobol) b.sobol.resize(b.lane_count);
  hit_columns(ctx, lights);
  path_columns(ctx, sobol);
  draw_numbers(ctx, depth, lights, rules.roulette);
  light_columns(ctx, lights);
  shade_lanes(ctx.lanes.isa, ctx.lanes.materials, b.shade);
  finish_vertices(ctx.lanes.isa, rules, b.shade, lights ? &b.light_queries : nullptr, b.vertices);
  if (lights) write_shadow_rays(ctx);
  write_next_rays(ctx);
}

}  // namespace raylane::path_detail
