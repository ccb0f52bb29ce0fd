// The stage that shades the lane_vertices queue at once, in columns: sort_arrivals lists each
// vertex as the wavefront arrives; the tracer writes their surfaces straight into the batches'
// columns, and a few passes copy the listed hits, rays and paths into the rest, a column group
// per pass (a pass over all thirty columns at once reloaded each column's pointer per row);
// then the rows' numbers (Sobol groups in lanes) and light points (render/lights/lights.h,
// sample_many) fill columns, and the scatter kernel (render/vertex_lanes.h: the BSDF, then the
// shadow rays and next rays, in one pass of float lanes) reads them; lane_write_back.cpp writes
// the rays and the paths back. (Each step once gathered what it needed from the hits and paths
// itself: seven passes over the rows, 18 % of a render.)
#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <vector>

#include "raylane/render/materials/bsdf.h"
#include "raylane/render/materials/texturing.h"
#include "render/wavefront/stages.h"

namespace raylane::path_detail {

namespace {

// The BSDF group's numbers for row r: (u1, u2, lobe) and roulette's (0 where this depth has
// no roulette), rounded below 1 into the float columns.
void set_bsdf_numbers(ThreadContext& ctx, std::size_t r, const std::array<double, 4>& u,
                      double u_roulette) {
  ShadeBatch& sb = ctx.wave.lane_vertices.shade;
  sb.u1[r] = unit_float(u[0]), sb.u2[r] = unit_float(u[1]), sb.u_lobe[r] = unit_float(u[2]);
  ctx.wave.lane_vertices.vertices.u_roulette[r] = unit_float(u_roulette);
}

// The light group's numbers for row r: (u1, u2, u_light, u_part), the cone's rounded below 1
// into its float columns.
void set_light_numbers(LightQueries& q, std::size_t r, const std::array<double, 4>& u) {
  q.cones.u1[r] = unit_float(u[0]), q.cones.u2[r] = unit_float(u[1]);
  q.u_light[r] = u[2], q.u_part[r] = u[3];
}

// The rows' numbers: Sobol groups for all of them at once in lanes, or MT19937 row by row in
// the double shading's order (light, BSDF, roulette where the row has it).
void draw_numbers(ThreadContext& ctx, bool lights, bool roulette) {
  Wavefront& w = ctx.wave;
  LaneVertexQueue& lv = w.lane_vertices;
  LightQueries& q = lv.light_queries;
  if (ctx.settings.sampler != Sampler::kSobol) {
    for (std::size_t r = 0; r < lv.count; ++r) {
      const PathState& p = w.paths[lv.path[r]];
      const uint32_t depth = lv.depth[r];
      if (lights) set_light_numbers(q, r, draw(ctx, p, Dims::light_group(depth), kLightDrawOrder));
      auto u = draw(ctx, p, Dims::bsdf_group(depth), kBsdfDrawOrder);
      set_bsdf_numbers(ctx, r, u, vertex_rules(ctx, depth).roulette ? ctx.rng.uniform() : 0.0);
    }
    return;
  }
  // Sobol: each group in lanes, its numbers written straight into the columns that read them.
  SobolBatch& s = lv.sobol;
  if (lights) {  // only the numbers the lights read (for one sphere light, no table gathers)
    const int read = ctx.lights.numbers_read();
    SobolNumbers to;  // the cone's numbers in float, the light's choice and part in double
    to.as_float = {q.cones.u1.data(), q.cones.u2.data(), nullptr, nullptr};
    to.as_double = {nullptr, nullptr, read > 2 ? q.u_light.data() : nullptr,
                    read > 3 ? q.u_part.data() : nullptr};
    s.seed.swap(lv.light_seed);  // the rows' seeds for their light groups, and back
    detail::sobol_groups(ctx.lanes.kernels, ctx.pass, 0, s, first_components(read), to);
    s.seed.swap(lv.light_seed);
  }
  // Roulette's number only where a row has roulette (the vertex lanes read it only then).
  // The lobe's number only where a material has more than one lobe (else 0, which picks the
  // diffuse lobe as every number in [0, 1) would): for a diffuse-only scene below roulette's
  // depth, no table gathers at all.
  ShadeBatch& sb = lv.shade;
  const bool lobe = !ctx.lanes.materials.lobe_unread;
  if (!lobe) std::fill_n(sb.u_lobe.begin(), lv.count, 0.0f);
  SobolNumbers to;
  to.as_float = {sb.u1.data(), sb.u2.data(), lobe ? sb.u_lobe.data() : nullptr, nullptr};
  if (roulette) to.as_float[3] = lv.vertices.u_roulette.data();
  s.seed.swap(lv.bsdf_seed);
  detail::sobol_groups(ctx.lanes.kernels, ctx.pass, 0, s,
                       3u | (lobe ? 4u : 0u) | (roulette ? 8u : 0u), to);
  s.seed.swap(lv.bsdf_seed);
}

// Three columns swapped for the life of the object, and back.
class LentPoints {
 public:
  using Columns = std::array<std::vector<float>, 3>;
  LentPoints(Columns& a, Columns& b) : a_(a), b_(b) { swap(); }
  ~LentPoints() { swap(); }
  LentPoints(const LentPoints&) = delete;
  LentPoints& operator=(const LentPoints&) = delete;

 private:
  void swap() {
    for (std::size_t k = 0; k < 3; ++k)
      a_[k].swap(b_[k]);
  }
  Columns &a_, &b_;
};

// The rows' light points (sphere lights in lanes), with the float direction the BSDF is
// evaluated toward written by the light sampler as it samples (ConeBatch::wi_float; 0 for no
// sample, and for every row without lights). The vertex lanes read the rest where sample_many
// left it.
void light_columns(ThreadContext& ctx, bool lights) {
  Wavefront& w = ctx.wave;
  LaneVertexQueue& lv = w.lane_vertices;
  ShadeBatch& sb = lv.shade;
  if (!lights) {
    for (int k = 0; k < 3; ++k)
      std::fill_n(sb.light_wi[k].begin(), lv.count, 0.0f);
    return;
  }
  PhaseClock clock(ctx.settings.time_phases);
  ConeBatch& cones = lv.light_queries.cones;
  cones.wi_float = {sb.light_wi[0].data(), sb.light_wi[1].data(), sb.light_wi[2].data()};
  {
    // The points the sampler reads (cones.ref) are the vertices' own columns, lent by a swap
    // for the call (a copy cost a pass over three columns) and given back when the scope ends,
    // also if the call throws. Both are padded to whole batches; the padding rows' answers are
    // unread.
    const LentPoints lent(lv.vertices.p, cones.ref);
    ctx.lights.sample_many(ctx.lanes.isa, lv.light_queries);
  }
  // The columns may move before the next step's call.
  cones.wi_float = {};
  clock.lap(ctx.stats.phases.lights);
}

}  // namespace

void start_lane_vertices(ThreadContext& ctx, std::size_t most) {
  Wavefront& w = ctx.wave;
  LaneVertexQueue& lv = w.lane_vertices;
  lv.count = 0;
  lv.grow(most);
  lv.shade.resize(most);
  lv.vertices.resize(most);
  if (samples_lights(ctx)) lv.light_queries.resize(most);
  if (ctx.settings.sampler == Sampler::kSobol) lv.sobol.resize(most);
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

// The queued rows' surfaces, straight into the batches' columns: the float point, its error
// bound and the geometric normal for the scatter kernel and the light sampler, the shading
// normal for the BSDF; dot(ns, d) and the facing into the rows' own columns.
void surface_columns(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  LaneVertexQueue& lv = w.lane_vertices;
  VertexBatch& vb = lv.vertices;
  ShadeBatch& sb = lv.shade;
  const SurfaceColumns out{vb.p[0].data(),       vb.p[1].data(),       vb.p[2].data(),
                           vb.ng[0].data(),      vb.ng[1].data(),      vb.ng[2].data(),
                           sb.n[0].data(),       sb.n[1].data(),       sb.n[2].data(),
                           vb.p_error[0].data(), vb.p_error[1].data(), vb.p_error[2].data(),
                           lv.cos_ns.data(),     lv.front.data()};
  ctx.tracer.surfaces(w.rays.rays, w.hits, {lv.ray.data(), lv.count}, out, w.scratch);
}

// Whether row r's BSDF reflects something: a shading normal at a right angle to the ray, or not
// finite, or a material without lobes is Bsdf::black(), as the double shading decides it.
bool reflects(const uint8_t* has_lobes, double cos_ns, uint32_t m) {
  return cos_ns != 0 && std::isfinite(cos_ns) && has_lobes[m];
}

// Whether every queued row's BSDF reflects something, in a loop without a branch per row that
// the compiler vectorises: the shading normal's test per row, the materials' only where some
// material shaded in lanes is black (a byte per row from a table does not vectorise). The
// row-by-row scan, a branch and a table byte per row, now runs only where some row does not.
bool all_reflect(const LaneVertexQueue& rows, const LaneMaterials& lm, std::size_t n) {
  const double* cos_ns = rows.cos_ns.data();
  unsigned ok = 1;
  for (std::size_t r = 0; r < n; ++r)
    ok &= unsigned(cos_ns[r] != 0) & unsigned(std::abs(cos_ns[r]) <= DBL_MAX);
  if (lm.any_black) {
    const uint32_t* material = rows.material.data();
    for (std::size_t r = 0; r < n; ++r)
      ok &= lm.has_lobes[material[r]];
  }
  return ok != 0;
}

// The queued rows whose BSDF reflects something, kept in order with their columns so far (the
// rest dropped). Seldom any to drop: one pass finds out, a second moves rows only then.
void drop_black_rows(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  LaneVertexQueue& lv = w.lane_vertices;
  const LaneMaterials& lm = ctx.lanes.materials;
  LaneVertexQueue& rows = lv;
  const std::size_t n = lv.count;
  if (all_reflect(rows, lm, n)) return;
  const double* cos_ns = rows.cos_ns.data();
  const uint32_t* material = rows.material.data();
  std::size_t first = 0;
  const uint8_t* has_lobes = lm.has_lobes.data();
  while (first < n && reflects(has_lobes, cos_ns[first], material[first]))
    ++first;
  const Columns3Out<float> p(lv.vertices.p), p_error(lv.vertices.p_error), ng(lv.vertices.ng);
  const Columns3Out<float> ns(lv.shade.n), beta(lv.vertices.beta);
  std::size_t kept = first;
  for (std::size_t r = first + 1; r < n; ++r) {
    if (!reflects(has_lobes, cos_ns[r], material[r])) continue;
    rows.path[kept] = rows.path[r], rows.ray[kept] = rows.ray[r], rows.depth[kept] = rows.depth[r];
    rows.material[kept] = rows.material[r], rows.front[kept] = rows.front[r];
    rows.light_seed[kept] = rows.light_seed[r], rows.bsdf_seed[kept] = rows.bsdf_seed[r];
    lv.vertices.survival[kept] = lv.vertices.survival[r];
    p.move(kept, r), p_error.move(kept, r), ng.move(kept, r), ns.move(kept, r);
    beta.move(kept, r);
    ++kept;
  }
  lv.count = kept;
}

// The rows' material into the BSDF's column, and their paths' times for the light sampler.
void hit_columns(ThreadContext& ctx, bool lights) {
  Wavefront& w = ctx.wave;
  LaneVertexQueue& lv = w.lane_vertices;
  // The same bits (material indices are below 2^31): one copy, where a loop converted each.
  static_assert(sizeof(uint32_t) == sizeof(int32_t));
  std::memcpy(lv.shade.material.data(), lv.material.data(), lv.count * sizeof(uint32_t));
  if (!lights) return;
  lv.light_queries.set_times(lv.path.data(), w.path_time);  // a moving light's time
}

// A textured scene's rows' own Kd and lobe probabilities (ShadeBatch::per_row_kd): a textured
// material's Kd times its image at the hit, as the double shading makes it (texture_factor on
// the same point and normal, so the same Kd in float), the others their material's.
void texture_columns(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  LaneVertexQueue& lv = w.lane_vertices;
  ShadeBatch& sb = lv.shade;
  const LaneMaterials& lm = ctx.lanes.materials;
  sb.per_row_kd = lm.any_textured;
  if (!lm.any_textured) return;
  const Scene& scene = ctx.tracer.scene();
  const VertexBatch& vb = lv.vertices;
  const Columns3Out<float> kd(sb.kd_at);
  for (std::size_t r = 0; r < lv.count; ++r) {
    const uint32_t m = lv.material[r];
    if (!lm.textured[m]) {
      kd.set(r, glm::vec3(lm.kd[0][m], lm.kd[1][m], lm.kd[2][m]));
      sb.pd_at[r] = lm.pd[m], sb.pr_at[r] = lm.pr[m], sb.pt_at[r] = lm.pt[m];
      continue;
    }
    const Material& material = scene.materials[m];
    const glm::dvec3 p(vb.p[0][r], vb.p[1][r], vb.p[2][r]);
    const glm::dvec3 ng(vb.ng[0][r], vb.ng[1][r], vb.ng[2][r]);
    const PrimRef prim = PrimRef::from_bits(w.hits.prim[lv.ray[r]]);
    const glm::vec3 textured(glm::dvec3(material.kd) *
                             texture_factor(scene, material, prim, Surface{p, ng, ng}));
    kd.set(r, textured);
    const LobeChances c = lobe_chances(textured, material.ks, material.kt);
    sb.pd_at[r] = c.pd, sb.pr_at[r] = c.pr, sb.pt_at[r] = c.pt;
  }
}

// The rows' directions turned around (wo, from the stream's float rays), and Beer's law on the
// segment just travelled for the rows that met a back face: their throughput, which
// sort_arrivals took as it was, again from what the ray carries times the transmittance (in
// double, then rounded, as the double shading). Beer's law is 1 on a front face.
void path_columns(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  LaneVertexQueue& lv = w.lane_vertices;
  const LaneVertexQueue& rows = lv;
  const std::size_t n = lv.count;
  ctx.lanes.kernels.gather_wo(w.rays.rays, rows.ray.data(), n, lv.shade);
  if (!ctx.lanes.materials.any_absorbing) return;
  const PathCarry& carry = w.rays.carry;
  const std::vector<Material>& materials = ctx.tracer.scene().materials;
  const Columns3Out<float> beta(lv.vertices.beta);
  const float* t = w.hits.t.data();
  const uint8_t* front = rows.front.data();
  for (std::size_t r = 0; r < n; ++r) {
    if (front[r]) continue;
    const uint32_t k = rows.ray[r];
    const glm::dvec3 carried(carry.beta[0][k], carry.beta[1][k], carry.beta[2][k]);
    beta.set(r, carried * beer_transmittance(materials[rows.material[r]], false, t[k]));
  }
}

}  // namespace

void shade_lane_vertices(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  LaneVertexQueue& lv = w.lane_vertices;
  const bool lights = samples_lights(ctx), sobol = ctx.settings.sampler == Sampler::kSobol;
  VertexRules rules = vertex_rules(ctx, 0);
  surface_columns(ctx);
  drop_black_rows(ctx);
  if (lv.count == 0) return;
  lv.shade.resize(lv.count);  // these set the sizes and padding
  lv.vertices.resize(lv.count);
  if (lights) lv.light_queries.resize(lv.count);
  if (sobol) lv.sobol.resize(lv.count);
  hit_columns(ctx, lights);
  texture_columns(ctx);
  path_columns(ctx);
  rules.roulette = lv.any_roulette;  // the survival column came with the rows (arrival.cpp)
  draw_numbers(ctx, lights, rules.roulette);
  light_columns(ctx, lights);
  scatter_lane_vertices(ctx, rules, lights);
}

}  // namespace raylane::path_detail
