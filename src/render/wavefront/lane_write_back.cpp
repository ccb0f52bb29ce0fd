// The lane shading's last passes: the vertex lanes' shadow rays and next rays, filtered in lanes
// into the next_shadows and next_rays queues, and the throughputs back to the paths.
#include <algorithm>
#include <limits>
#include <type_traits>

#include "render/wavefront/stages.h"

namespace raylane::path_detail {

namespace {

// The three columns of c as pointers, taken once per pass: the passes below read a dozen
// columns per row, more than the registers that would keep the vectors' own pointers.
template <class T>
struct Column3View {
  const T *x, *y, *z;
  explicit Column3View(const std::array<std::vector<T>, 3>& c)
      : x(c[0].data()), y(c[1].data()), z(c[2].data()) {}
  glm::vec<3, T> operator[](std::size_t r) const { return {x[r], y[r], z[r]}; }
};

// Room for `rows` more rows at the end of a stream (trimmed by the caller to what was kept).
std::size_t grow_stream(RayStream& s, std::size_t rows, bool aimed) {
  const std::size_t at = s.size();
  s.resize(at + rows);
  if (aimed) s.aim.resize(at + rows);
  return at;
}

}  // namespace

// The vertex lanes' shadow rays queued, each aimed at its light: the origin and end as the
// lanes rounded them, the direction as the BSDF was evaluated toward it (the light point's,
// rounded to float), and each one's query. A filter over the rows, in lanes.
void write_lane_shadow_rays(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  LaneVertexQueue& lv = w.lane_vertices;
  const VertexBatch& vb = lv.vertices;
  const std::size_t n = lv.count;
  ShadowQueue& q = w.next_shadows;
  RayStream& s = q.rays;
  const std::size_t at = grow_stream(s, n, true), queued = q.size();
  q.resize_queries(queued + n);
  static_assert(sizeof(PrimRef) == 4 && std::is_trivially_copyable_v<PrimRef>,
                "a light's PrimRef is its 32 bits");
  RowFilter f;
  f.keep = vb.shadow_ok.data();
  f.add(vb.shadow_o[0].data(), s.ox.data() + at);
  f.add(vb.shadow_o[1].data(), s.oy.data() + at);
  f.add(vb.shadow_o[2].data(), s.oz.data() + at);
  f.add(lv.shade.light_wi[0].data(), s.dx.data() + at);
  f.add(lv.shade.light_wi[1].data(), s.dy.data() + at);
  f.add(lv.shade.light_wi[2].data(), s.dz.data() + at);
  f.add(vb.shadow_tmax.data(), s.tmax.data() + at);
  f.add(reinterpret_cast<const uint32_t*>(lv.light_queries.light.data()), s.aim.data() + at);
  f.add(lv.path.data(), q.path.data() + queued);
  for (std::size_t k = 0; k < 3; ++k)
    f.add(vb.shadow_c[k].data(), q.contribution[k].data() + queued);
  const std::size_t kept = ctx.lanes.kernels.filter_rows(f, n);
  std::fill_n(s.tmin.begin() + std::ptrdiff_t(at), kept, 0.0f);
  s.resize(at + kept), s.aim.resize(at + kept);
  q.resize_queries(queued + kept);
}

// The vertex lanes' throughputs back to the paths (every row: a path that ends here is not
// read again, and the write spares a branch per row), then the next rays of the paths that go
// on and their list, filtered in lanes.
void write_lane_next_rays(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  LaneVertexQueue& lv = w.lane_vertices;
  const VertexBatch& vb = lv.vertices;
  const std::size_t n = lv.count;
  const Column3View<float> beta(vb.next_beta), p(vb.p);
  const float* pdf = lv.shade.pdf.data();
  const uint32_t* row_path = lv.path.data();
  PathState* paths = w.paths.data();
  for (std::size_t r = 0; r < n; ++r) {
    PathState& path = paths[row_path[r]];
    path.beta = beta[r];
    path.prev_p = p[r];
    path.prev_pdf = pdf[r];
    path.prev_specular = false;
  }
  RayStream& s = w.next_rays.rays;
  Column<uint32_t>& next_paths = w.next_rays.path;
  const std::size_t at = grow_stream(s, n, false), listed = next_paths.size();
  next_paths.resize(listed + n);
  RowFilter f;
  f.keep = vb.alive.data();
  for (std::size_t k = 0; k < 3; ++k)
    f.add(vb.next_o[k].data(), (k == 0 ? s.ox : k == 1 ? s.oy : s.oz).data() + at);
  for (std::size_t k = 0; k < 3; ++k)
    f.add(lv.shade.wi[k].data(), (k == 0 ? s.dx : k == 1 ? s.dy : s.dz).data() + at);
  f.add(row_path, next_paths.data() + listed);
  const std::size_t kept = ctx.lanes.kernels.filter_rows(f, n);
  std::fill_n(s.tmin.begin() + std::ptrdiff_t(at), kept, 0.0f);
  std::fill_n(s.tmax.begin() + std::ptrdiff_t(at), kept, std::numeric_limits<float>::infinity());
  s.resize(at + kept);
  next_paths.resize(listed + kept);
}

}  // namespace raylane::path_detail
