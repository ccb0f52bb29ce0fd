// sample_cones (render/lights/light_lanes.h) in float lanes, instantiated per instruction set by
// src/render/render_lanes_<isa>.cpp. Include from nowhere else. The steps are sphere_cone's
// (prims/sphere_cone.h) on float lanes: the scalar float instance's answers bit for bit.
#pragma once

#include "raylane/prims/area_light_sample.h"
#include "raylane/prims/box_faces.h"
#include "raylane/prims/cylinder_light.h"
#include "raylane/prims/sphere_cone.h"
#include "raylane/prims/triangle_light.h"
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

// store_wi_float in the lanes of `taken` only, the others' wi_float kept (the area kernel's
// rows among the cone kernel's and those sampled one by one).
template <class A>
void store_wi_float_in(const ConeBatch& b, std::size_t i, const simd::FloatVec3<A>& wi,
                       const ConeFloats<A>& pdf, const simd::Mask<A>& taken) {
  auto old = [&](std::size_t k) { return simd::load<A>(b.wi_float[k] + i); };
  const simd::FloatVec3<A> merged{simd::select(taken, wi.x, old(0)),
                                  simd::select(taken, wi.y, old(1)),
                                  simd::select(taken, wi.z, old(2))};
  // An untaken lane's pdf is set positive, so its old direction is stored as it was.
  using F = ConeFloats<A>;
  store_wi_float<A>(b, i, merged, simd::select(taken, pdf, F(1.0f)));
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

// The light's corners of every lane taking the kind's route, gathered from the table's columns
// (`rows` holds the lanes' table rows, 0 in the others: a valid row whenever one lane takes the
// route).
template <class A, std::size_t kCount>
std::array<ConeFloats<A>, kCount> gather_columns(const std::array<const float*, kCount>& columns,
                                                 const simd::Ints<A>& rows) {
  std::array<ConeFloats<A>, kCount> out;
  for (std::size_t c = 0; c < kCount; ++c)
    out[c] = simd::gather<A>(columns[c], rows);
  return out;
}

// The answers so far of rows [i, i + W), and where a route's lanes overwrite them.
template <class A>
struct AreaLaneAnswers {
  simd::FloatVec3<A> wi;
  ConeFloats<A> dist, pdf;
  void take(const simd::Mask<A>& m, const AreaLightSample<ConeFloats<A>, simd::FloatVec3<A>>& s) {
    wi = {simd::select(m, s.wi.x, wi.x), simd::select(m, s.wi.y, wi.y),
          simd::select(m, s.wi.z, wi.z)};
    dist = simd::select(m, s.dist, dist);
    pdf = simd::select(m, s.pdf, pdf);
  }
};

// sample_area_lights: triangle_light_point, box_face_point and cylinder_light_point, each with
// area_light_sample, on
// float lanes, each row about its own light; a block of rows computes only the routes its rows
// take, and keeps the other rows' answers.
template <class A>
void sample_area_lights_range(ConeBatch& b, const double* u_part, const AreaLightRows& rows,
                              const AreaLightTables& tables) {
  using F = ConeFloats<A>;
  using I = simd::Ints<A>;
  using V = simd::FloatVec3<A>;
  constexpr std::size_t W = simd::kWidth<A>;
  for (std::size_t i = 0; i < b.size(); i += W) {
    const I route = simd::load<A>(rows.route + i);
    const simd::Mask<A> live = simd::first_lanes<A>(int(b.size() - i));
    const simd::Mask<A> tri = simd::equal<A>(route, I(kAreaRouteTriangle)) & live;
    const simd::Mask<A> box = simd::equal<A>(route, I(kAreaRouteBox)) & live;
    const simd::Mask<A> cyl = simd::equal<A>(route, I(kAreaRouteCylinder)) & live;
    const simd::Mask<A> taken = tri | box | cyl;
    if (simd::none<A>(taken)) continue;
    const I index = simd::load<A>(rows.index + i);
    const V ref = simd::load3<A>(b.ref, i);
    const F u1 = simd::load<A>(b.u1.data() + i), u2 = simd::load<A>(b.u2.data() + i);
    const F choice = simd::load<A>(b.choice.data() + i);
    AreaLaneAnswers<A> out{simd::load3<A>(b.wi, i), simd::load<A>(b.dist.data() + i),
                           simd::load<A>(b.pdf.data() + i)};
    if (simd::any<A>(tri)) {
      const auto c = gather_columns<A>(tables.triangle, simd::select<A>(tri, index, I(0)));
      const TriangleLightPoint<F, V> t = triangle_light_point<F>(
          V{c[0], c[1], c[2]}, V{c[3], c[4], c[5]}, V{c[6], c[7], c[8]}, u1, u2);
      out.take(tri, area_light_sample<true>(ref, t.p, t.n, t.area, choice));
    }
    if (simd::any<A>(box)) {
      const auto c = gather_columns<A>(tables.box, simd::select<A>(box, index, I(0)));
      const V lo{c[0], c[1], c[2]}, hi{c[3], c[4], c[5]};
      const BoxFacePoint<F, V> face =
          box_face_point<F>(lo, hi, ref, simd::load_narrowed<A>(u_part + i), u1, u2);
      out.take(box, area_light_sample<false>(ref, face.p, face.n, face.area, choice));
    }
    if (simd::any<A>(cyl)) {
      const auto c = gather_columns<A>(tables.cylinder, simd::select<A>(cyl, index, I(0)));
      const V axis{c[3] * c[6], c[4] * c[6], c[5] * c[6]};  // unit axis times height
      const CylinderLightPoint<F, V> x = cylinder_light_point<F>(
          V{c[0], c[1], c[2]}, axis, c[7], ref, simd::load_narrowed<A>(u_part + i), u1, u2);
      out.take(cyl, area_light_sample<false>(ref, x.p, x.n, x.area, choice));
    }
    simd::store3<A>(b.wi, i, out.wi);
    simd::store<A>(b.dist.data() + i, out.dist);
    simd::store<A>(b.pdf.data() + i, out.pdf);
    if (b.wi_float[0]) store_wi_float_in<A>(b, i, out.wi, out.pdf, taken);
  }
}

}  // namespace raylane::detail
