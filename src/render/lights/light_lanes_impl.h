// sample_cones (render/lights/light_lanes.h) in float lanes, instantiated per instruction set by
// src/render/render_lanes_<isa>.cpp. Include from nowhere else. The steps are sphere_cone's
// (prims/sphere_cone.h) on float lanes: the scalar float instance's answers bit for bit.
#pragma once

#include "raylane/prims/area_light_sample.h"
#include "raylane/prims/box_faces.h"
#include "raylane/prims/sphere_cone.h"
#include "raylane/render/lights/light_lanes.h"
#include "raylane/simd/lane_convert.h"
#include "raylane/simd/lane_numbers.h"
#include "raylane/simd/lane_rows.h"

namespace raylane::detail {

template <class A>
using ConeFloats = simd::Floats<A>;

// The sphere of rows [i, i + W): the batch's columns, or every_row's broadcast.
template <class A>
struct ConeSphereLanes {
  simd::FloatVec3<A> center;
  ConeFloats<A> radius, choice;
  ConeSphereLanes(const ConeBatch& b, const ConeSphere* every_row, std::size_t i) {
    using F = ConeFloats<A>;
    if (every_row) {
      const ConeSphere& s = *every_row;
      center = {F(s.center[0]), F(s.center[1]), F(s.center[2])};
      radius = F(s.radius), choice = F(s.choice);
      return;
    }
    center = simd::load3<A>(b.center, i);
    radius = simd::load<A>(b.radius.data() + i);
    choice = simd::load<A>(b.choice.data() + i);
  }
};

// ConeBatch::wi_float for rows [i, i + W): wi where pdf > 0 in a row below the batch's size,
// else 0 (a padding row's sphere may be any, so its direction is not written).
template <class A>
void store_wi_float(const ConeBatch& b, std::size_t i, const simd::FloatVec3<A>& wi,
                    const ConeFloats<A>& pdf) {
  using F = ConeFloats<A>;
  const auto keep = (pdf > F(0.0f)) & simd::first_lanes<A>(int(b.size() - i));
  simd::store<A>(b.wi_float[0] + i, simd::select(keep, wi.x, F(0.0f)));
  simd::store<A>(b.wi_float[1] + i, simd::select(keep, wi.y, F(0.0f)));
  simd::store<A>(b.wi_float[2] + i, simd::select(keep, wi.z, F(0.0f)));
}

template <class A>
void sample_cones_range(ConeBatch& b, const ConeSphere* every_row) {
  using F = ConeFloats<A>;
  constexpr std::size_t W = simd::kWidth<A>;
  for (std::size_t i = 0; i < b.size(); i += W) {
    const ConeSphereLanes<A> sphere(b, every_row, i);
    const SphereCone<F, simd::FloatVec3<A>> s =
        sphere_cone<F>(sphere.center, sphere.radius, simd::load3<A>(b.ref, i),
                       simd::load<A>(b.u1.data() + i), simd::load<A>(b.u2.data() + i));
    simd::store3<A>(b.wi, i, s.wi);
    simd::store<A>(b.dist.data() + i, s.dist);
    simd::store<A>(b.solid_angle.data() + i, s.solid_angle);
    const F pdf = simd::select(s.solid_angle > F(0.0f), sphere.choice / s.solid_angle, F(0.0f));
    simd::store<A>(b.pdf.data() + i, pdf);
    if (b.wi_float[0]) store_wi_float<A>(b, i, s.wi, pdf);
  }
}

// sample_box_faces: box_face_point and area_light_sample (one-sided) on float lanes, every
// row about the one box.
template <class A>
void sample_box_faces_range(ConeBatch& b, const double* u_part, const ConeBox& box) {
  using F = ConeFloats<A>;
  using V = simd::FloatVec3<A>;
  constexpr std::size_t W = simd::kWidth<A>;
  const V lo{F(box.lo[0]), F(box.lo[1]), F(box.lo[2])},
      hi{F(box.hi[0]), F(box.hi[1]), F(box.hi[2])};
  const F choice(box.choice);
  for (std::size_t i = 0; i < b.size(); i += W) {
    const V ref = simd::load3<A>(b.ref, i);
    const BoxFacePoint<F, V> face =
        box_face_point<F>(lo, hi, ref, simd::load_narrowed<A>(u_part + i),
                          simd::load<A>(b.u1.data() + i), simd::load<A>(b.u2.data() + i));
    const AreaLightSample<F, V> s =
        area_light_sample<false>(ref, face.p, face.n, face.area, choice);
    simd::store3<A>(b.wi, i, s.wi);
    simd::store<A>(b.dist.data() + i, s.dist);
    simd::store<A>(b.pdf.data() + i, s.pdf);
    if (b.wi_float[0]) store_wi_float<A>(b, i, s.wi, s.pdf);
  }
}

}  // namespace raylane::detail
