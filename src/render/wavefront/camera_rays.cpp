// The wavefront's first stage: a tile's paths and their camera rays; and the AOVs of the camera
// rays' hits.
#include <algorithm>

#include "raylane/render/camera/camera_lanes.h"
#include "raylane/render/materials/texturing.h"
#include "render/wavefront/stages.h"

namespace raylane::path_detail {

namespace {

// A tile's paths, 4×4 blocks of pixels at a time (y counts up in the pixel grid), into the
// slots from `first` on, before their camera rays: pixel and Sobol scramble, and the pixel's
// corner in the camera's points. Returns how many.
uint32_t tile_paths(ThreadContext& ctx, const Camera& cam, uint32_t x0, uint32_t y0,
                    uint32_t first) {
  std::vector<PathState>& paths = ctx.wave.paths;
  CameraPoints& points = ctx.wave.camera;
  if (paths.size() < first + kTile * kTile) paths.resize(first + kTile * kTile);
  const uint32_t x1 = std::min(x0 + kTile, cam.width), y1 = std::min(y0 + kTile, cam.height);
  points.resize(std::size_t(x1 - x0) * (y1 - y0));
  double *px = points.x.data(), *py = points.y.data();  // locals: the stores may alias them
  PathState* path = paths.data() + first;
  const uint64_t image_seed = ctx.settings.seed;
  uint32_t i = 0;
  for (uint32_t by = y0; by < y1; by += kBlock)
    for (uint32_t bx = x0; bx < x1; bx += kBlock)
      for (uint32_t y = by; y < std::min(by + kBlock, y1); ++y)
        for (uint32_t x = bx; x < std::min(bx + kBlock, x1); ++x, ++i) {
          PathState& p = path[i];
          p.pixel = std::size_t(cam.height - 1 - y) * cam.width + x;
          p.pixel_seed = mix64(image_seed ^ mix64(p.pixel));
          p.radiance = glm::dvec3(0, 0, 0);
          px[i] = double(x), py[i] = double(y);
        }
  return i;
}

// The pinhole's camera rays with Sobol numbers: the jitter from the lanes straight into the
// points' columns, the rays from the camera's lanes (bit for bit what the loop below makes).
void pinhole_sobol_rays(ThreadContext& ctx, const Camera& cam, RayStream& rays) {
  Wavefront& w = ctx.wave;
  CameraPoints& points = w.camera;
  SobolNumbers to;
  to.as_double = {points.jx.data(), points.jy.data(), nullptr, nullptr};
  detail::sobol_groups(ctx.lanes.kernels, ctx.pass, Dims::camera, w.lane_vertices.sobol,
                       first_components(2), to);
  detail::pinhole_rays(
      ctx.lanes.kernels, cam,
      {points.x.data(), points.y.data(), points.jx.data(), points.jy.data(), rays.size()}, rays);
}

// A scene that moves: the time of each path in slots [first, first + n), one more number of its
// camera sample (Sobol's group of its own, Dims::time; MT19937's next number after the tile's
// camera numbers). A scene that does not move draws nothing and keeps no times.
void draw_path_times(ThreadContext& ctx, uint32_t first, uint32_t n) {
  Wavefront& w = ctx.wave;
  if (!ctx.tracer.scene().moves()) return;
  if (w.path_time.size() < w.paths.size()) w.path_time.resize(w.paths.size());
  const bool sobol = ctx.settings.sampler == Sampler::kSobol;
  for (std::size_t i = first; i < first + n; ++i) {
    const double u =
        sobol ? sobol_group(w.paths[i].pixel_seed, ctx.pass, Dims::time)[0] : ctx.rng.uniform();
    w.path_time[i] = unit_float(u);  // in [0, 1): never rounded up to the shutter's closing
  }
}

// The time column of a queue's rays: ray k gets path[k]'s time.
void stamp_stream(RayStream& rays, const Column<uint32_t>& path,
                  const std::vector<float>& path_time) {
  rays.time.resize(rays.size());
  for (std::size_t k = 0; k < rays.size(); ++k)
    rays.time[k] = path_time[path[k]];
}

}  // namespace

void stamp_times(ThreadContext& ctx) {
  Wavefront& w = ctx.wave;
  if (w.path_time.empty()) return;
  stamp_stream(w.rays.rays, w.rays.path, w.path_time);
  stamp_stream(w.shadows.rays, w.shadows.path, w.path_time);
}

uint32_t make_camera_rays(ThreadContext& ctx, const Camera& cam, uint32_t x0, uint32_t y0,
                          uint32_t first, RayQueue& into) {
  Wavefront& w = ctx.wave;
  const uint32_t n = tile_paths(ctx, cam, x0, y0, first);
  const PathState* paths = w.paths.data() + first;
  RayStream& rays = into.rays;
  into.clear();
  rays.resize(n);
  into.path.resize(n);
  for (uint32_t i = 0; i < n; ++i)
    into.path[i] = first + i;
  into.carry.resize(n);
  into.carry.fill(0, n, Carried{});  // depth 0, throughput 1
  const bool sobol = ctx.settings.sampler == Sampler::kSobol;
  SobolBatch& s = w.lane_vertices.sobol;
  if (sobol) {
    s.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      s.seed[i] = paths[i].pixel_seed;
    if (!cam.has_lens()) {
      pinhole_sobol_rays(ctx, cam, rays);
      draw_path_times(ctx, first, n);
      return n;
    }
    detail::sobol_groups(ctx.lanes.kernels, ctx.pass, Dims::camera, s);
  }
  const CameraPoints& points = w.camera;
  for (std::size_t i = 0; i < n; ++i) {
    const PathState& p = paths[i];
    std::array<double, 4> u;
    if (sobol)
      for (int c = 0; c < 4; ++c)
        u[std::size_t(c)] = s.u[std::size_t(c)][i] * 0x1p-32;
    else  // the lens's numbers only with a lens: a pinhole render draws what it always drew
      u = cam.has_lens() ? draw(ctx, p, Dims::camera, {0, 1, 2, 3})
                         : draw(ctx, p, Dims::camera, {0, 1});
    rays.set(i, ray_cast<float>(
                    cam.ray_through_lens(points.x[i] + u[0], points.y[i] + u[1], u[2], u[3])));
  }
  draw_path_times(ctx, first, n);
  return n;
}

// The AOVs of the camera samples (render/film/aov.h) from this step's hits: rays
// [0, Wavefront::camera_rays) are camera rays, and the step has their records. A sample that
// meets nothing adds zeros.
void add_camera_aovs(const ThreadContext& ctx, Film& film) {
  const Scene& scene = ctx.tracer.scene();
  const Wavefront& w = ctx.wave;
  const std::vector<Hit>& hits = w.records;
  const AovSet set = film.aovs;
  const std::size_t stride = std::size_t(set.channels());
  for (std::size_t k = 0; k < w.camera_rays; ++k) {
    const Hit& h = hits[k];
    if (!h.hit()) continue;
    const std::size_t at = film.slot(w.paths[w.rays.path[k]].pixel);
    if (at == Film::kNotStored) continue;
    double* out = &film.aov_sum[at * stride];
    auto add = [&](Aov a, const glm::dvec3& v) {
      if (!set.has(a)) return;
      double* at = out + set.offset(a);
      for (int k = 0; k < aov_channels(a); ++k)
        at[k] += v[k];
    };
    if (set.has(Aov::kAlbedo)) add(Aov::kAlbedo, albedo_at(scene, h.prim, h.surface));
    add(Aov::kNormal, h.surface.ns);
    add(Aov::kDepth, {h.t, h.t, h.t});
    add(Aov::kPosition, h.surface.p);
  }
}

}  // namespace raylane::path_detail
