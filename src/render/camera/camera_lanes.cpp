#include "raylane/render/camera/camera_lanes.h"

#include <algorithm>

#include "render/render_lanes.h"

namespace raylane {

void detail::pinhole_rays(const RenderLanes& lanes, const Camera& cam, const PixelPoints& points,
                          RayStream& out) {
  const std::size_t n = points.size, done = lanes.pinhole_rays(cam, points, out);
  // What every ray shares: the eye and the ray's whole length (ray_through's Rayd{eye, d}).
  const Rayf shared = ray_cast<float>(Rayd{cam.eye, {0, 0, 1}});
  std::fill_n(out.ox.begin(), n, shared.o.x);
  std::fill_n(out.oy.begin(), n, shared.o.y);
  std::fill_n(out.oz.begin(), n, shared.o.z);
  std::fill_n(out.tmin.begin(), n, shared.tmin);
  std::fill_n(out.tmax.begin(), n, shared.tmax);
  for (std::size_t i = done; i < n; ++i)  // the last points, fewer than a lane batch
    out.set(i, ray_cast<float>(
                   cam.ray_through(points.x[i] + points.jx[i], points.y[i] + points.jy[i])));
}

void pinhole_rays(Isa isa, const Camera& cam, const PixelPoints& points, RayStream& out) {
  detail::pinhole_rays(detail::render_lanes(isa), cam, points, out);
}

}  // namespace raylane
