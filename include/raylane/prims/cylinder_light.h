// A point on the parts of a cylinder light that face a shading point, written once over the
// number type (core/numbers.h): N = double for the double shading
// (Cylinder::sample_area_seen_from, Cylinder::area_seen_from), N = float lanes for the render's
// light points (src/render/lights/light_lanes_impl.h), and N = float as the lanes' bit-for-bit
// reference. No step fuses a multiply-add and the build has -ffp-contract=off, so the float
// lanes and the scalar float text agree on every instruction set. The sample it makes is
// prims/area_light_sample.h's (one-sided: a cylinder emits from its outside).
//
// What a point p outside the cylinder can see of it: at most one cap (the top where p lies
// beyond it along the axis, the base where it lies below), and of the side only points whose
// outward normal ρ has (p − q)·ρ > 0. For a side point q = b + u·t + r·ρ that is p⊥·ρ > r, p⊥
// the part of p − b across the axis: it does not depend on the height t, it can hold only
// within the half of the side about p⊥ (p⊥·ρ > 0), and nowhere where |p⊥| ≤ r. Drawn by area
// over that cap and that half side (the side only where |p⊥| > r); the density by area divides
// by their area. The arc truly seen is narrower (its half-angle is acos(r/|p⊥|)), but bounding
// it needs an arc cosine the lanes lack; the half needs a sine and a cosine of the number, and
// still leaves out the half of the side and the cap that all-over sampling drew for nothing.
//
// Float's range is the limit: a cylinder whose axis's squared length or whose side's area
// overflows float (an axis beyond about 1.8e19) gives no sample in the lanes (a density of 0
// or NaN), where the double shading would still draw it.
#pragma once

#include "raylane/core/frame_steps.h"
#include "raylane/core/numbers.h"

namespace raylane {

// The cylinder from base b along `axis` (base to top-cap centre) with radius r: its unit axis
// and height, the axis normalised here, so that the side's points lie on it to the number
// type's precision (a stored unit axis is a few float roundings off unit, and an error across
// the side grows by 1/cos at a grazing ray: 3e-8 became 2e-5 in a shadow ray's distance).
template <class N, class V3>
struct CylinderAxis {
  V3 u;
  N h;
};

template <class N, class V3>
CylinderAxis<N, V3> cylinder_axis(const V3& axis) {
  using K = Num<N>;
  const N h = K::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
  return {V3{axis.x / h, axis.y / h, axis.z / h}, h};
}

// The areas of the cap and the half side that face `ref` (0 for a part that does not), whether
// the cap is the top one, and the unit direction from the axis toward ref (meaningless where the
// side has no area).
template <class N, class V3>
struct CylinderPartsSeen {
  N side, cap;
  typename Num<N>::Mask top;
  V3 out;
  N total() const { return side + cap; }
};

template <class N, class V3>
CylinderPartsSeen<N, V3> cylinder_parts_seen(const V3& b, const CylinderAxis<N, V3>& a, const N& r,
                                             const V3& ref) {
  using K = Num<N>;
  using M = typename K::Mask;
  constexpr double kPi = 3.14159265358979323846;
  const N zero(0.0);
  const V3& u = a.u;
  const V3 rel{ref.x - b.x, ref.y - b.y, ref.z - b.z};
  const N along = rel.x * u.x + rel.y * u.y + rel.z * u.z;
  const V3 perp{rel.x - u.x * along, rel.y - u.y * along, rel.z - u.z * along};
  const N d = K::sqrt(perp.x * perp.x + perp.y * perp.y + perp.z * perp.z);
  CylinderPartsSeen<N, V3> s;
  s.side = K::select(d > r, N(kPi) * r * a.h, zero);
  s.top = along > a.h;
  s.cap = K::select(M(s.top | (along < zero)), N(kPi) * r * r, zero);
  s.out = V3{perp.x / d, perp.y / d, perp.z / d};
  return s;
}

// A point uniform by area on the parts that face `ref`, its outward normal and their area.
// area 0 where nothing faces ref (inside the cylinder, or within its radius and between its
// caps' planes): then p and n are meaningless.
template <class N, class V3>
struct CylinderLightPoint {
  V3 p, n;
  N area;
};

// u_part picks the part in proportion to its area (the side where its share holds the number
// or the cap has none); on the side u1 is the height and u2 the angle across the half, θ =
// π·(u2 − ½) from the direction toward ref; on the cap u1 is the squared radius and u2 the turn
// about the axis (core/frame_steps.h's frame).
template <class N, class V3>
CylinderLightPoint<N, V3> cylinder_light_point(const V3& b, const V3& axis, const N& r,
                                               const V3& ref, const N& u_part, const N& u1,
                                               const N& u2) {
  using K = Num<N>;
  using M = typename K::Mask;
  const N zero(0.0);
  const CylinderAxis<N, V3> a = cylinder_axis<N>(axis);
  const V3& u = a.u;
  const N& h = a.h;
  const CylinderPartsSeen<N, V3> s = cylinder_parts_seen<N>(b, a, r, ref);
  const N area = s.total();
  const M take_side = M((s.side > zero) & M((u_part * area < s.side) | (s.cap == zero)));
  // The side: ρ = cos θ·e + sin θ·f, e toward ref and f = u × e; cos θ = sin(π·u2) and
  // sin θ = −cos(π·u2).
  const TurnSinCos<N> half = sincos_turn(N(0.5) * u2);
  const V3 e = s.out;
  const V3 f{u.y * e.z - u.z * e.y, u.z * e.x - u.x * e.z, u.x * e.y - u.y * e.x};
  const N sin_t = K::negate(half.cos);
  const V3 rho{e.x * half.sin + f.x * sin_t, e.y * half.sin + f.y * sin_t,
               e.z * half.sin + f.z * sin_t};
  const N t = u1 * h;
  const V3 side{b.x + u.x * t + rho.x * r, b.y + u.y * t + rho.y * r, b.z + u.z * t + rho.z * r};
  // The cap: radius r·√u1 at the turn u2, on the top's plane or the base's.
  const TurnSinCos<N> turn = sincos_turn(u2);
  const V3 radial = frame_to_world<N>(u, V3{turn.cos, turn.sin, zero});
  const N rr = r * K::sqrt(u1);
  const N lift = K::select(s.top, h, zero);
  const V3 cap{b.x + u.x * lift + radial.x * rr, b.y + u.y * lift + radial.y * rr,
               b.z + u.z * lift + radial.z * rr};
  const V3 cap_n{K::select(s.top, u.x, K::negate(u.x)), K::select(s.top, u.y, K::negate(u.y)),
                 K::select(s.top, u.z, K::negate(u.z))};
  CylinderLightPoint<N, V3> out;
  out.p = V3{K::select(take_side, side.x, cap.x), K::select(take_side, side.y, cap.y),
             K::select(take_side, side.z, cap.z)};
  out.n = V3{K::select(take_side, rho.x, cap_n.x), K::select(take_side, rho.y, cap_n.y),
             K::select(take_side, rho.z, cap_n.z)};
  out.area = area;
  return out;
}

}  // namespace raylane
