// A point on a box light's faces that face a shading point, written once over the number type
// (core/numbers.h): N = double for the double shading (Box::sample_area_seen_from,
// Box::area_seen_from), N = float lanes for the render's light points
// (src/render/lights/light_lanes_impl.h), and N = float as the lanes' bit-for-bit reference. No
// step fuses a multiply-add and the build has -ffp-contract=off, so the float lanes and the
// scalar float text agree on every instruction set. The sample it makes is
// prims/area_light_sample.h's.
//
// A box emits from its outside only, and a point outside it sees at most three of its faces,
// one per axis: the hi face where the point lies beyond hi, the lo face where it lies below
// lo. Drawing from those faces alone, by area, wastes no sample on a face turned away (with
// all six faces about half the samples were), and the density by area divides by their area.
//
// In float each step rounds once: the point's coordinates on the face are the corners and a
// number, a few roundoffs of the corners, and the coordinate across the face is the face's
// own. Float's range is the limit: a face whose area underflows is never drawn, and one whose
// area or distance overflows gives no sample (a density beyond range), where the double
// shading would still draw it.
#pragma once

#include "raylane/core/numbers.h"

namespace raylane {

// The areas of the faces of the box [lo, hi] that face `ref`, one per axis (0 for an axis
// whose faces neither does: ref within the box's slab), and whether it is the hi face.
template <class N, class V3>
struct BoxFacesSeen {
  N area[3];
  typename Num<N>::Mask hi[3];
  N total() const { return area[0] + area[1] + area[2]; }
};

template <class N, class V3>
BoxFacesSeen<N, V3> box_faces_seen(const V3& lo, const V3& hi, const V3& ref) {
  using K = Num<N>;
  using M = typename K::Mask;
  const N zero(0.0);
  const V3 d{hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  BoxFacesSeen<N, V3> f;
  f.hi[0] = ref.x > hi.x, f.hi[1] = ref.y > hi.y, f.hi[2] = ref.z > hi.z;
  f.area[0] = K::select(M(f.hi[0] | (ref.x < lo.x)), d.y * d.z, zero);
  f.area[1] = K::select(M(f.hi[1] | (ref.y < lo.y)), d.z * d.x, zero);
  f.area[2] = K::select(M(f.hi[2] | (ref.z < lo.z)), d.x * d.y, zero);
  return f;
}

// A point on the faces of the box [lo, hi] that face `ref`, uniform by area over them, its
// outward normal (one component ±1) and the faces' area. area 0 where no face faces ref
// (ref in the closed box): then p and n are meaningless.
template <class N, class V3>
struct BoxFacePoint {
  V3 p, n;
  N area;
};

// u_part picks the face in proportion to its area (the first face whose share holds it; a
// face of zero area, one below float's range, never); u1 and u2 place the point on it, along
// the next axes in cyclic order.
template <class N, class V3>
BoxFacePoint<N, V3> box_face_point(const V3& lo, const V3& hi, const V3& ref, const N& u_part,
                                   const N& u1, const N& u2) {
  using K = Num<N>;
  using M = typename K::Mask;
  const N zero(0.0), one(1.0);
  const V3 d{hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  const BoxFacesSeen<N, V3> f = box_faces_seen<N>(lo, hi, ref);
  const N ax = f.area[0], ay = f.area[1], az = f.area[2];
  const M hi_x = f.hi[0], hi_y = f.hi[1], hi_z = f.hi[2];
  const N area = f.total();
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

}  // namespace raylane
