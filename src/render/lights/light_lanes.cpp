#include "raylane/render/lights/light_lanes.h"

#include "render/render_lanes.h"

namespace raylane {

namespace {
// AVX-512's float lanes: the scatter kernel reads the light points in batches of sixteen rows.
constexpr std::size_t kMaxWidth = 16;
}  // namespace

void ConeBatch::resize(std::size_t rows) {
  size_ = rows;
  std::size_t padded = (rows + kMaxWidth - 1) / kMaxWidth * kMaxWidth;
  if (radius.size() < padded) {  // the columns only grow: a wavefront's batch is refilled
    for (auto* v : {&ref, &center, &wi})
      for (Column& c : *v)
        c.resize(padded);
    for (Column* c : {&radius, &u1, &u2, &choice, &dist, &solid_angle, &pdf})
      c->resize(padded);
  }
  // Padding rows: a unit sphere two units from the origin (with a ConeSphere for every row,
  // they see that sphere instead). Their answers, finite or not, are unread: the render lends
  // its vertices' point columns as `ref` (lane_vertices.cpp), whose padding holds whatever an
  // earlier wavefront left there.
  for (std::size_t i = rows; i < padded; ++i) {
    for (int k = 0; k < 3; ++k)
      ref[k][i] = 0, center[k][i] = k == 2 ? 2 : 0;
    radius[i] = 1, u1[i] = u2[i] = 0.5f, choice[i] = 1;
  }
}

void sample_cones(Isa isa, ConeBatch& batch, const ConeSphere* every_row) {
  detail::render_lanes(isa).sample_cones(batch, every_row);
}

void sample_box_faces(Isa isa, ConeBatch& batch, const double* u_part, const ConeBox& box) {
  detail::render_lanes(isa).sample_box_faces(batch, u_part, box);
}

void sample_area_lights(Isa isa, ConeBatch& batch, const double* u_part, const AreaLightRows& rows,
                        const AreaLightTables& tables) {
  detail::render_lanes(isa).sample_area_lights(batch, u_part, rows, tables);
}

}  // namespace raylane
