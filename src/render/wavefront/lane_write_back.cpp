// The lane shading's last pass: the scatter kernel (render/vertex_lanes.h), which packs its shadow
// rays and next rays straight into the next_shadows and next_rays queues as it makes them, then
// the throughputs back to the paths.
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

// Room for `rows` more rows at the end of a stream, as many as the kernel's whole registers
// store (VertexQueues): the caller trims it to what was queued.
std::size_t grow_stream(RayStream& s, std::size_t rows, bool aimed) {
  const std::size_t at = s.size(), room = (rows + 15) / 16 * 16;
  s.resize(at + room);
  if (aimed) s.aim.resize(at + room);
  return at;
}

// The rows' paths get the vertex's throughput, point and BSDF density (every row: a path that
// ends here is not read again, and the write spares a branch per row).
void write_back_paths(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  const LaneVertexQueue& lv = w.lane_vertices;
  const VertexBatch& vb = lv.vertices;
  const Column3View<float> beta(vb.next_beta), p(vb.p);
  const float* pdf = lv.shade.pdf.data();
  const uint32_t* row_path = lv.path.data();
  PathState* paths = w.paths.data();
  for (std::size_t r = 0; r < lv.count; ++r) {
    PathState& path = paths[row_path[r]];
    path.beta = beta[r];
    path.prev_p = p[r];
    path.prev_pdf = pdf[r];
    path.prev_specular = false;
  }
}

}  // namespace

void scatter_lane_vertices(ThreadContext& ctx, const VertexRules& rules, bool lights) {
  Wavefront& w = ctx.wave;
  LaneVertexQueue& lv = w.lane_vertices;
  const std::size_t n = lv.count;
  VertexQueues q;
  q.path = lv.path.data();
  RayStream& next = w.next_rays.rays;
  Column<uint32_t>& next_paths = w.next_rays.path;
  const std::size_t next_at = grow_stream(next, n, false), listed = next_paths.size();
  next_paths.resize(next.size());
  q.next_o = {next.ox.data() + next_at, next.oy.data() + next_at, next.oz.data() + next_at};
  q.next_d = {next.dx.data() + next_at, next.dy.data() + next_at, next.dz.data() + next_at};
  q.next_path = next_paths.data() + listed;
  ShadowQueue& sq = w.next_shadows;
  RayStream& shadow = sq.rays;
  std::size_t shadow_at = shadow.size(), queued = sq.size();
  static_assert(sizeof(PrimRef) == 4 && std::is_trivially_copyable_v<PrimRef>,
                "a light's PrimRef is its 32 bits");
  if (lights) {
    shadow_at = grow_stream(shadow, n, true);
    sq.resize_queries(queued + shadow.size() - shadow_at);
    q.shadow_o = {shadow.ox.data() + shadow_at, shadow.oy.data() + shadow_at,
                  shadow.oz.data() + shadow_at};
    q.shadow_d = {shadow.dx.data() + shadow_at, shadow.dy.data() + shadow_at,
                  shadow.dz.data() + shadow_at};
    q.shadow_tmax = shadow.tmax.data() + shadow_at;
    q.shadow_light = shadow.aim.data() + shadow_at;
    q.shadow_path = sq.path.data() + queued;
    for (std::size_t k = 0; k < 3; ++k)
      q.shadow_c[k] = sq.contribution[k].data() + queued;
  }
  ctx.lanes.kernels.scatter_vertices(ctx.lanes.materials, rules, lv.shade,
                                     lights ? &lv.light_queries : nullptr, lv.vertices, q);
  std::fill_n(next.tmin.begin() + std::ptrdiff_t(next_at), q.next_count, 0.0f);
  std::fill_n(next.tmax.begin() + std::ptrdiff_t(next_at), q.next_count,
              std::numeric_limits<float>::infinity());
  next.resize(next_at + q.next_count);
  next_paths.resize(listed + q.next_count);
  if (lights) {
    std::fill_n(shadow.tmin.begin() + std::ptrdiff_t(shadow_at), q.shadow_count, 0.0f);
    shadow.resize(shadow_at + q.shadow_count), shadow.aim.resize(shadow_at + q.shadow_count);
    sq.resize_queries(queued + q.shadow_count);
  }
  write_back_paths(ctx);
}

}  // namespace raylane::path_detail
