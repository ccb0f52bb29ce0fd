// The lane shading's last pass: the scatter kernel (render/vertex_lanes.h), which packs its shadow
// rays and next rays straight into the next_shadows and next_rays queues as it makes them, the
// next rays with what they carry of their paths.
#include <algorithm>
#include <limits>
#include <type_traits>

#include "render/wavefront/stages.h"

namespace raylane::path_detail {

namespace {

// Room for `rows` more rows at the end of a stream, as many as the kernel's whole registers
// store (VertexQueues): the caller trims it to what was queued.
std::size_t grow_stream(RayStream& s, std::size_t rows, bool aimed) {
  const std::size_t at = s.size(), room = (rows + 15) / 16 * 16;
  s.resize(at + room);
  if (aimed) s.aim.resize(at + room);
  return at;
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
  q.depth = lv.depth.data();
  PathCarry& carry = w.next_rays.carry;
  carry.resize(next.size());
  q.next_beta = {carry.beta[0].data() + listed, carry.beta[1].data() + listed,
                 carry.beta[2].data() + listed};
  q.next_prev_p = {carry.prev_p[0].data() + listed, carry.prev_p[1].data() + listed,
                   carry.prev_p[2].data() + listed};
  q.next_prev_pdf = carry.prev_pdf.data() + listed, q.next_depth = carry.depth.data() + listed;
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
  carry.resize(listed + q.next_count);
  std::fill_n(carry.prev_specular.begin() + std::ptrdiff_t(listed), q.next_count, uint8_t(0));
  if (lights) {
    std::fill_n(shadow.tmin.begin() + std::ptrdiff_t(shadow_at), q.shadow_count, 0.0f);
    shadow.resize(shadow_at + q.shadow_count), shadow.aim.resize(shadow_at + q.shadow_count);
    sq.resize_queries(queued + q.shadow_count);
  }
}

}  // namespace raylane::path_detail
