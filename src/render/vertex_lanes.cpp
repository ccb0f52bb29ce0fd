#include "raylane/render/vertex_lanes.h"

#include "raylane/render/vertex_steps.h"
#include "render/render_lanes.h"

namespace raylane {

namespace {
constexpr std::size_t kMaxWidth = 16;  // AVX-512's float lanes: every batch is padded to it
}

void VertexBatch::resize(std::size_t rows) {
  size_ = rows;
  std::size_t padded = (rows + kMaxWidth - 1) / kMaxWidth * kMaxWidth;
  if (alive.size() < padded) {  // the columns only grow, as ShadeBatch's
    for (auto* v : {&beta, &p, &p_error, &ng, &next_beta, &shadow_o, &next_o})
      for (Column& c : *v)
        c.resize(padded);
    for (Column* c : {&u_roulette, &survival, &shadow_ok, &alive, &shadow_tmax})
      c->resize(padded);
    for (std::vector<double>& c : shadow_c)
      c.resize(padded);
  }
}

void finish_vertices(Isa isa, const VertexRules& rules, const ShadeBatch& bsdf,
                     const LightQueries* lights, VertexBatch& batch) {
  detail::render_lanes(isa).finish_vertices(rules, bsdf, lights, batch);
}

void gather_wo(Isa isa, const RayStream& rays, const uint32_t* rows, std::size_t n,
               ShadeBatch& shade) {
  detail::render_lanes(isa).gather_wo(rays, rows, n, shade);
}

void scatter_vertices(Isa isa, const LaneMaterials& materials, const VertexRules& rules,
                      ShadeBatch& bsdf, const LightQueries* lights, VertexBatch& batch,
                      VertexQueues& queues) {
  detail::render_lanes(isa).scatter_vertices(materials, rules, bsdf, lights, batch, queues);
}

}  // namespace raylane
