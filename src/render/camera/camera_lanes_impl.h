// pinhole_rays (render/camera/camera_lanes.h) in double lanes, instantiated per instruction set by
// src/render/render_lanes_<isa>.cpp. Include from nowhere else. The direction is
// pinhole_direction (render/camera/camera.h) on double lanes, the text Camera::ray_through runs
// at double.
#pragma once

#include "raylane/render/camera/camera_lanes.h"
#include "raylane/simd/lane_convert.h"
#include "raylane/simd/lane_numbers.h"
#include "raylane/simd/lanes.h"

namespace raylane::detail {

template <class A>
std::size_t pinhole_rays_range(const Camera& cam, const PixelPoints& pts, RayStream& out) {
  using D = simd::Doubles<A>;
  constexpr std::size_t W = std::size_t(simd::kDoubleWidth<A>);
  const std::size_t whole = pts.size / W * W;
  for (std::size_t i = 0; i < whole; i += W) {
    const D x = D::load_unaligned(pts.x + i) + D::load_unaligned(pts.jx + i);
    const D y = D::load_unaligned(pts.y + i) + D::load_unaligned(pts.jy + i);
    const simd::DoubleVec3<A> d = pinhole_direction<D, simd::DoubleVec3<A>>(cam, x, y);
    simd::store_narrowed<A>(out.dx.data() + i, d.x);
    simd::store_narrowed<A>(out.dy.data() + i, d.y);
    simd::store_narrowed<A>(out.dz.data() + i, d.z);
  }
  return whole;
}

}  // namespace raylane::detail
