// One ray made ready for single-ray traversal (trace/ray_traverse.h): the ray in every lane,
// its reciprocal direction, slab sides and shear frame worked out once in scalar code and
// broadcast. The packet set-up (RayShear, SlabSides) does the same work in every lane with
// selects and mask extractions; for one ray that is a tenth of the single-ray tracer's time
// (profile of the 1.31M mesh's shadow rays). Same operations, same roundings: a ray gets the
// same frame bit for bit either way (tests/trace/single_ray_test.cpp). Lane code: included only
// by the per-ISA translation units.
#pragma once

#include <cfloat>
#include <cmath>
#include <utility>

#include "raylane/simd/packet.h"

namespace raylane {

// A ray as scalars: what a stream or one lane of a packet holds.
struct RayScalars {
  float o[3], d[3], inv[3];
  float tmin, tmax;
  float time = 0.5f;  // in the shutter interval (core/ray.h)
};

// Whether a ray is traced at all: finite origin and direction, a non-zero direction and
// tmin <= tmax (false for NaN); the packet path's test (simd_tracer_impl.h), lane for lane.
inline bool single_ray_valid(const RayScalars& r) {
  auto finite = [](float v) { return std::fabs(v) <= FLT_MAX; };
  float dd = r.d[0] * r.d[0] + r.d[1] * r.d[1] + r.d[2] * r.d[2];
  return finite(r.o[0]) && finite(r.o[1]) && finite(r.o[2]) && finite(r.d[0]) && finite(r.d[1]) &&
         finite(r.d[2]) && dd > 0.0f && r.tmin <= r.tmax;
}

// A ray's shear frame as scalars: the axes and the factors RayShear holds in each lane.
struct ShearScalars {
  float sx, sy, sz;
  int kx, ky, kz;
};

// The watertight test's frame (Woop et al. 2013, §3) as RayShear computes it per lane: z is
// the axis of largest |d| (ties to the lowest), x and y follow cyclically, swapped when
// d_z < 0. (A template only so that each per-ISA unit keeps its own copy.)
template <class L>
inline ShearScalars scalar_shear(const RayScalars& r) {
  float ax = std::fabs(r.d[0]), ay = std::fabs(r.d[1]), az = std::fabs(r.d[2]);
  int kz = (ax >= ay && ax >= az) ? 0 : (ay >= az) ? 1 : 2;
  int kx = (kz + 1) % 3, ky = (kz + 2) % 3;
  if (r.d[kz] < 0.0f) std::swap(kx, ky);
  float sz = 1.0f / r.d[kz];
  return {r.d[kx] * sz, r.d[ky] * sz, sz, kx, ky, kz};
}

// The frame in every lane, from scalars (no division: they were divided once), written in
// place: a RayShear returned by value was copied into the packet through the stack, a
// store-forwarding stall on every ray.
template <class L>
inline void broadcast_shear(const ShearScalars& f, RayShear<L>& s) {
  using F = simd::Floats<L>;
  s.sz = F(f.sz), s.sx = F(f.sx), s.sy = F(f.sy);
  for (int k = 0; k < 3; ++k) {
    s.x_is[k] = simd::Mask<L>(f.kx == k);
    s.y_is[k] = simd::Mask<L>(f.ky == k);
    s.z_is[k] = simd::Mask<L>(f.kz == k);
  }
  s.uniform = true;
  s.kx = f.kx, s.ky = f.ky, s.kz = f.kz;
}

// The ray in every lane of a packet whose lanes are all active, with its frame when the caller
// has it (else scalar_shear's). Contract: single_ray_valid(r).
template <class L>
inline RayPacket<L> broadcast_ray(const RayScalars& r, const ShearScalars* frame = nullptr) {
  using F = simd::Floats<L>;
  RayPacket<L> p;
  p.ox = F(r.o[0]), p.oy = F(r.o[1]), p.oz = F(r.o[2]);
  p.dx = F(r.d[0]), p.dy = F(r.d[1]), p.dz = F(r.d[2]);
  p.inv_dx = F(r.inv[0]), p.inv_dy = F(r.inv[1]), p.inv_dz = F(r.inv[2]);
  p.tmin = F(r.tmin);
  p.time = F(r.time);
  p.aim = simd::Ints<L>(int32_t(PrimRef::kInvalidBits));  // single rays go through closest hit
  p.active = simd::Mask<L>(true);
  broadcast_shear<L>(frame ? *frame : scalar_shear<L>(r), p.shear);
  p.sides.uniform = true;
  for (int k = 0; k < 3; ++k) {
    bool hi = r.inv[k] < 0.0f;  // the sign of d, even for ±0 (docs/hard-cases.md B3)
    p.sides.hi_first[k] = simd::Mask<L>(hi);
    p.sides.hi_first_bits[k] = hi ? (1u << simd::kWidth<L>)-1 : 0u;
    p.sides.near_hi[k] = hi;
  }
  return p;
}

}  // namespace raylane
