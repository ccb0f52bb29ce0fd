// pinhole_rays (render/camera_lanes.h) in double lanes, instantiated per instruction set by
// src/render/render_lanes_<isa>.cpp. Include from nowhere else. The steps are Camera::ray_through's
// in its order: d = normalize(right·(dx·rx) + up·(dy·ry) + forward), dx = 2x/W − 1, and
// normalize(a) = a / sqrt(a·a) with the dot product summed x, y, z.
#pragma once

#include "raylane/render/camera_lanes.h"
#include "raylane/simd/lanes.h"

namespace raylane::detail {

template <class A>
std::size_t pinhole_rays_range(const Camera& cam, const PixelPoints& pts, RayStream& out) {
  using D = simd::Doubles<A>;
  constexpr std::size_t W = std::size_t(simd::kDoubleWidth<A>);
  const std::size_t whole = pts.size / W * W;
  const D width(double(cam.width)), height(double(cam.height)), two(2.0), one(1.0);
  const D rx(cam.rx), ry(cam.ry);
  for (std::size_t i = 0; i < whole; i += W) {
    const D x = D::load_unaligned(pts.x + i) + D::load_unaligned(pts.jx + i);
    const D y = D::load_unaligned(pts.y + i) + D::load_unaligned(pts.jy + i);
    const D sx = two * x / width - one, sy = two * y / height - one;
    const D a = sx * rx, b = sy * ry;
    const D dx = D(cam.right.x) * a + D(cam.up.x) * b + D(cam.forward.x);
    const D dy = D(cam.right.y) * a + D(cam.up.y) * b + D(cam.forward.y);
    const D dz = D(cam.right.z) * a + D(cam.up.z) * b + D(cam.forward.z);
    const D len = simd::sqrt<A>(dx * dx + dy * dy + dz * dz);
    simd::store_narrowed<A>(out.dx.data() + i, dx / len);
    simd::store_narrowed<A>(out.dy.data() + i, dy / len);
    simd::store_narrowed<A>(out.dz.data() + i, dz / len);
  }
  return whole;
}

}  // namespace raylane::detail
