// A point on a box light's faces that face a shading point, and the light sample it makes,
// written once over the number type (core/numbers.h): N = double for the double shading
// (Box::sample_area_seen_from and LightSampler's conversion by area), N = float lanes for the
// render's light points (src/render/lights/light_lanes_impl.h), and N = float as the lanes'
// bit-for-bit reference. No step fuses a multiply-add and the build has -ffp-contract=off, so
// the float lanes and the scalar float text agree on every instruction set.
//
// A box emits from its outside only, and a point outside it sees at most three of its faces,
// one per axis: the hi face where the point lies beyond hi, the lo face where it lies below
// lo. Drawing from those faces alone, by area, wastes no sample on a face turned away (with
// all six faces about half the samples were), and the density by area divides by their area.
//
// Float's error, relative to the float unit roundoff u = 2^-24 (each step rounds once;
// tests/render/light_lanes_test.cpp holds the float answers to this against the double steps
// at the same inputs): the point's coordinates on the face a few roundoffs of the box's
// corners, the one across the face exact (the face's own plane); the direction and distance
// a few roundoffs of the point's distance from the shading point beyond that; the cosine at the
// light exact given the direction (one component of it); the density a few roundoffs relative.
#pragma once

#include <cmath>

#include "raylane/core/numbers.h"

namespace raylane {

// A point on the faces of the box [lo, hi] that face `ref`, uniform by area over them, its
// outward normal (one component ±1) and the faces' area. area 0 where no face faces ref
// (inside the box, or on the planes of its faces): then p and n are meaningless.
template <class N, class V3>
struct BoxFacePoint {
  V3 p, n;
  N area;
};

// u_part picks the face in proportion to its area (the first face whose share holds it; faces
// of zero area, a flat box's edges, never); u1 and u2 place the point on it, along the next
// axes in cyclic order.
template <class N, class V3>
BoxFacePoint<N, V3> box_face_point(const V3& lo, const V3& hi, const V3& ref, const N& u_part,
                                   const N& u1, const N& u2) {
  using K = Num<N>;
  using M = typename K::Mask;
  const N zero(0.0), one(1.0);
  const V3 d{hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  const M hi_x = ref.x > hi.x, hi_y = ref.y > hi.y, hi_z = ref.z > hi.z;
  const M seen_x = M(hi_x | (ref.x < lo.x)), seen_y = M(hi_y | (ref.y < lo.y)),
          seen_z = M(hi_z | (ref.z < lo.z));
  const N ax = K::select(seen_x, d.y * d.z, zero), ay = K::select(seen_y, d.z * d.x, zero),
          az = K::select(seen_z, d.x * d.y, zero);
  const N area = ax + ay + az;
  // The face: x where its share holds the number or neither other face has area; else y where
  // its share does or z has none; else z.
  const N pick = u_part * area;
  const M none_after_x = M((ay == zero) & (az == zero));
  const M take_x = M((ax > zero) & M((pick < ax) | none_after_x));
  const M not_x = M(!take_x);
  const M take_y = M(not_x & M((ay > zero) & M((pick - ax < ay) | (az == zero))));
  const M take_z = M(not_x & M(!take_y));
  // The axis picked is on its face's plane; the next one in cyclic order takes u1, the one
  // after u2 (x: y, z; y: z, x; z: x, y).
  auto across = [&](const auto& take, const auto& is_hi, const N& l, const N& h, const N& u,
                    const N& size) {
    return K::select(take, K::select(is_hi, h, l), l + u * size);
  };
  BoxFacePoint<N, V3> out;
  out.p = V3{across(take_x, hi_x, lo.x, hi.x, K::select(take_y, u2, u1), d.x),
             across(take_y, hi_y, lo.y, hi.y, K::select(take_x, u1, u2), d.y),
             across(take_z, hi_z, lo.z, hi.z, K::select(take_x, u2, u1), d.z)};
  auto normal = [&](const auto& take, const auto& is_hi) {
    return K::select(take, K::select(is_hi, one, N(-1.0)), zero);
  };
  out.n = V3{normal(take_x, hi_x), normal(take_y, hi_y), normal(take_z, hi_z)};
  out.area = area;
  return out;
}

// The light sample a point on an emitter drawn by area makes from ref: the unit direction, the
// distance, and the density in solid angle, choice · d² / (cos θ_light · area); pdf 0 where
// the point is no sample (area 0, the point at ref, or seen edge-on or from behind).
template <class N, class V3>
struct AreaLightSample {
  V3 wi;
  N dist, pdf;
};

template <class N, class V3>
AreaLightSample<N, V3> area_light_sample(const V3& ref, const V3& p, const V3& n, const N& area,
                                         const N& choice) {
  using K = Num<N>;
  const N zero(0.0);
  const V3 to{p.x - ref.x, p.y - ref.y, p.z - ref.z};
  const N d2 = to.x * to.x + to.y * to.y + to.z * to.z;
  const N dist = K::sqrt(d2);
  AreaLightSample<N, V3> out;
  out.wi = V3{to.x / dist, to.y / dist, to.z / dist};
  out.dist = dist;
  const N cos_l = K::negate(out.wi.x * n.x + out.wi.y * n.y + out.wi.z * n.z);
  const N pdf = choice * d2 / (cos_l * area);
  // A density beyond the type's range (a point edge-on, or the area below it) is no sample;
  // the comparison is false for NaN too.
  using M = typename K::Mask;
  const M ok = M(M(M((area > zero) & (d2 > zero)) & (cos_l > zero)) & (pdf < N(HUGE_VAL)));
  out.pdf = K::select(ok, pdf, zero);
  return out;
}

}  // namespace raylane
