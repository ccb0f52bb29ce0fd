#include "raylane/render/vertex_lanes.h"

#include "raylane/render/vertex_steps.h"
#include "render/render_lanes.h"

namespace raylane {

namespace {
constexpr std::size_t kMaxWidth = 8;  // AVX-512's double lanes: every batch is padded to it
}

void VertexBatch::resize(std::size_t rows) {
  size_ = rows;
  std::size_t padded = (rows + kMaxWidth - 1) / kMaxWidth * kMaxWidth;
  if (t.size() < padded) {  // the columns only grow, as ShadeBatch's
    for (auto* v : {&beta, &p, &ng, &ray_o, &ray_d, &shadow_c, &next_beta})
      for (Column& c : *v)
        c.resize(padded);
    for (Column* c : {&t, &u_roulette, &survival, &shadow_ok, &alive})
      c->resize(padded);
    for (auto* v : {&shadow_o, &next_o})
      for (FloatColumn& c : *v)
        c.resize(padded);
    shadow_tmax.resize(padded);
  }
}

void finish_vertices(Isa isa, const VertexRules& rules, const ShadeBatch& bsdf,
                     const LightQueries* lights, VertexBatch& batch) {
  detail::render_lanes(isa).finish_vertices(rules, bsdf, lights, batch);
}

void gather_vertex_rays(Isa isa, const RayStream& rays, const uint32_t* rows, std::size_t n,
                        VertexBatch& vertices, ShadeBatch& shade) {
  detail::render_lanes(isa).gather_vertex_rays(rays, rows, n, vertices, shade);
}

std::size_t filter_rows(Isa isa, const RowFilter& filter, std::size_t rows) {
  return detail::render_lanes(isa).filter_rows(filter, rows);
}

bool shadow_contribution(const VertexRules& rules, const glm::dvec3& beta, const glm::dvec3& f,
                         const glm::dvec3& le, double light_pdf, double bsdf_pdf, glm::dvec3& c) {
  if (!(light_pdf > 0) || f == glm::dvec3(0, 0, 0)) return false;
  c = shadow_ray_contribution(rules.mis, beta, f, le, light_pdf, bsdf_pdf);
  return is_finite(c);
}

bool next_throughput(const VertexRules& rules, const glm::dvec3& beta, const glm::dvec3& value,
                     double pdf, double u_roulette, glm::dvec3& next) {
  if (!(pdf > 0)) return false;
  next = sampled_throughput(beta, value, pdf);
  if (rules.roulette) {
    if (u_roulette >= rules.survival) return false;
    next = survivor_throughput(next, rules.survival);
  }
  return is_finite(next) && next != glm::dvec3(0, 0, 0);
}

}  // namespace raylane
