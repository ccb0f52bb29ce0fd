// The texel lookup (render/materials/texel_lookup.h) for float lanes, for the shading kernels of the
// per-ISA translation units. Each active lane gets exactly what the scalar float lookup returns
// for its (u, v); inactive lanes get black. The texels of four corners are scattered in memory
// and stored in one of four forms, so each lane runs the scalar code: a gather would save
// only the coordinate arithmetic, which is not where a lookup's time goes.
#pragma once

#include "raylane/render/materials/texel_lookup.h"
#include "raylane/simd/lanes.h"

namespace raylane {

template <class A>
struct RgbLanes {
  simd::Floats<A> r, g, b;
};

namespace texel_lanes_detail {

template <class A, class Lookup>
RgbLanes<A> per_lane(const simd::Floats<A>& u, const simd::Floats<A>& v,
                     const simd::Mask<A>& active, Lookup lookup) {
  constexpr int W = simd::kWidth<A>;
  alignas(64) float us[W], vs[W], r[W], g[W], b[W];
  simd::store<A>(us, u);
  simd::store<A>(vs, v);
  uint32_t on = simd::bits<A>(active);
  for (int i = 0; i < W; ++i) {
    LinearRgb<float> c = (on >> i) & 1u ? lookup(us[i], vs[i]) : LinearRgb<float>{};
    r[i] = c.r, g[i] = c.g, b[i] = c.b;
  }
  return {simd::load<A>(r), simd::load<A>(g), simd::load<A>(b)};
}

}  // namespace texel_lanes_detail

template <class A>
RgbLanes<A> texture_texel_lookup_lanes(const TexelImage& img, const simd::Floats<A>& u,
                                       const simd::Floats<A>& v, const simd::Mask<A>& active) {
  return texel_lanes_detail::per_lane<A>(
      u, v, active, [&](float a, float b) { return texture_texel_lookup<float>(img, a, b); });
}

template <class A>
RgbLanes<A> environment_texel_lookup_lanes(const TexelImage& img, const simd::Floats<A>& u,
                                           const simd::Floats<A>& v, const simd::Mask<A>& active) {
  return texel_lanes_detail::per_lane<A>(
      u, v, active, [&](float a, float b) { return environment_texel_lookup<float>(img, a, b); });
}

}  // namespace raylane
