// Hit surfaces in lanes: what each kind's surface_lanes (double lanes) and surface_float_lanes
// (float lanes, with error bounds) take and give (prims/<kind>_packet.h). Lane code: included
// only through the kinds' packet headers by the SIMD tracer's per-ISA translation units. The
// double lanes run the double reference's steps (surface_ref) in its order; with
// -ffp-contract=off and IEEE division and square root in the lanes, the answers are the
// reference's bit for bit, and the float lanes' are the same steps' scalar float instance's
// (tests/trace/tracer_test.cpp checks both at every ISA).
#pragma once

#include "raylane/simd/lane_lookup.h"
#include "raylane/simd/lane_numbers.h"
#include "raylane/simd/lanes.h"

namespace raylane {

// One hit per lane: the ray as the packet kernels traced it (widened to double) and its t.
template <class A>
struct HitRayLanes {
  simd::DoubleVec3<A> o, d;
  simd::Doubles<A> t;
  // o + d·t, as Ray::at.
  simd::DoubleVec3<A> at() const { return {o.x + d.x * t, o.y + d.y * t, o.z + d.z * t}; }
};

// The point and the unit normal (geometric = shading for the quadrics and boxes).
template <class A>
struct SurfaceLanes {
  simd::DoubleVec3<A> p, n;
};

// One hit per float lane, for the render's float columns: the ray as traced and its t.
template <class A>
struct FloatHitRayLanes {
  simd::FloatVec3<A> o, d;
  simd::Floats<A> t;
  // The stream's time column (null where it has none: a scene that stands) and the lanes' rays
  // in it, for the kinds that read the time (moving spheres) to gather where they need it: a
  // batch of the other kinds loads nothing more.
  const float* time_column;
  const uint32_t* ray;
  simd::Floats<A> time() const {
    if (time_column == nullptr) return simd::Floats<A>(0.5f);
    return simd::gather<A>(time_column, simd::load<A>(reinterpret_cast<const int32_t*>(ray)));
  }
};

// The point, the unit geometric and shading normals (the same but for triangles) and a
// componentwise bound on the point's error, in float.
template <class A>
struct FloatSurfaceLanes {
  simd::FloatVec3<A> p, ng, ns, error;
};

// A FloatSurfaceLanes from its parts, assigned lane register by lane register: built as an
// aggregate from the kinds' surface structs, GCC moved the registers through the stack in
// pieces, some of them through general registers.
template <class A>
[[gnu::always_inline]] inline FloatSurfaceLanes<A> surface_lanes_of(
    const simd::FloatVec3<A>& p, const simd::FloatVec3<A>& ng, const simd::FloatVec3<A>& ns,
    const simd::FloatVec3<A>& error) {
  FloatSurfaceLanes<A> out;
  out.p.x = p.x, out.p.y = p.y, out.p.z = p.z;
  out.ng.x = ng.x, out.ng.y = ng.y, out.ng.z = ng.z;
  out.ns.x = ns.x, out.ns.y = ns.y, out.ns.z = ns.z;
  out.error.x = error.x, out.error.y = error.y, out.error.z = error.z;
  return out;
}

// The table column c read at one row per float lane: by register permutes where the table is
// short (a scene's handful of boxes or spheres), else gathered (simd/lane_lookup.h).
template <class A>
inline simd::Floats<A> read_rows(const std::vector<float>& c, const simd::Ints<A>& rows) {
  return simd::lookup<A>(c.data(), c.size(), rows);
}
template <class A>
inline simd::FloatVec3<A> read_rows3(const std::vector<float>& x, const std::vector<float>& y,
                                     const std::vector<float>& z, const simd::Ints<A>& rows) {
  return {read_rows<A>(x, rows), read_rows<A>(y, rows), read_rows<A>(z, rows)};
}

// a·b in glm::dot's order ((x + y) + z).
template <class A>
inline simd::Doubles<A> dot_lanes(const simd::DoubleVec3<A>& a, const simd::DoubleVec3<A>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// The table columns x, y, z read at one row per lane.
template <class A>
inline simd::DoubleVec3<A> load_rows3(const std::vector<float>& x, const std::vector<float>& y,
                                      const std::vector<float>& z, const uint32_t* rows) {
  return {simd::load_rows<A>(x, rows), simd::load_rows<A>(y, rows), simd::load_rows<A>(z, rows)};
}

}  // namespace raylane
