// A point on an emitting triangle, uniform by area, its unit normal and the triangle's area,
// written once over the number type (core/numbers.h): N = double for the double shading
// (Triangle::sample_area, Triangle::area), N = float lanes for the render's light points
// (src/render/lights/light_lanes_impl.h), and N = float as the lanes' bit-for-bit reference. No
// step fuses a multiply-add and the build has -ffp-contract=off, so the float lanes and the
// scalar float text agree on every instruction set. The sample it makes is
// prims/area_light_sample.h's (two-sided: a mesh is a surface, both sides emit).
//
// Uniform barycentrics by the square-root warp (Osada, Funkhouser, Chazelle and Dobkin, "Shape
// distributions", ACM TOG 21(4), 2002, §4.2; pbrt-v4 §6.5.4 uses another map of the same
// density): b0 = 1 − √u1, b1 = u2·√u1. The products and sums are in the order glm's cross, dot,
// normalize and length take them, so the double instance is the arithmetic the double shading had.
//
// In float: the point is a few roundoffs off the triangle's plane; the shadow ray aims at the
// light itself (Tracer::occluded skips it), so that offset does not block the sample. A
// triangle whose area underflows float, or whose edges' cross product overflows it, gives no
// sample (area 0 or a normal of NaN: area_light_sample's density is 0) where the double
// shading would still draw it.
#pragma once

#include "raylane/core/numbers.h"

namespace raylane {

template <class N, class V3>
struct TriangleLightPoint {
  V3 p, n;  // n is (p1 − p0) × (p2 − p0), normalised
  N area;
};

template <class N, class V3>
TriangleLightPoint<N, V3> triangle_light_point(const V3& p0, const V3& p1, const V3& p2,
                                               const N& u1, const N& u2) {
  using K = Num<N>;
  const N one(1.0);
  const N su = K::sqrt(u1);
  const N b0 = one - su, b1 = u2 * su, b2 = one - b0 - b1;
  TriangleLightPoint<N, V3> out;
  out.p = V3{p0.x * b0 + p1.x * b1 + p2.x * b2, p0.y * b0 + p1.y * b1 + p2.y * b2,
             p0.z * b0 + p1.z * b1 + p2.z * b2};
  const V3 e1{p1.x - p0.x, p1.y - p0.y, p1.z - p0.z}, e2{p2.x - p0.x, p2.y - p0.y, p2.z - p0.z};
  const V3 c{e1.y * e2.z - e2.y * e1.z, e1.z * e2.x - e2.z * e1.x, e1.x * e2.y - e2.x * e1.y};
  const N len = K::sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
  const N inv = one / len;
  out.n = V3{c.x * inv, c.y * inv, c.z * inv};
  out.area = N(0.5) * len;
  return out;
}

}  // namespace raylane
