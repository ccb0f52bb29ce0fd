// Ray and hit packets: W rays in SIMD lanes, structure of arrays (design.md, "Packets").
// Templates over the instruction set A; used only inside the per-ISA translation units.
#pragma once

#include <cstdint>
#include <limits>

#include "raylane/prims/prim_ref.h"
#include "raylane/simd/lanes.h"

namespace raylane {

template <class A>
struct RayPacket {
  using F = simd::Floats<A>;
  F ox, oy, oz;
  F dx, dy, dz;
  F inv_dx, inv_dy, inv_dz;  // 1/d: ±inf for a ±0 component, signed like d (hard-cases B3)
  F tmin;
  simd::Mask<A> active;  // lanes that hold a valid ray still being traced
};

template <class A>
struct HitPacket {
  simd::Floats<A> t;    // closest hit so far; starts at the ray's tmax
  simd::Ints<A> prim;   // PrimRef bits of that hit; PrimRef::kInvalidBits for none
  simd::Mask<A> found;  // lanes that found a hit
};

// The PrimRef bits of row `row` of kind `tag`, as an int32 lane value.
inline int32_t prim_bits(PrimTag tag, uint32_t row) {
  return int32_t(PrimRef(tag, row).bits());
}

// Records hit distance t as primitive `bits` in the lanes of `ok`.
template <class A>
inline void commit_hit(const simd::Floats<A>& t, const simd::Mask<A>& ok, int32_t bits,
                       HitPacket<A>& h) {
  h.t = simd::select<A>(ok, t, h.t);
  h.prim = simd::select<A>(ok, simd::Ints<A>(bits), h.prim);
  h.found = h.found | ok;
}

// For a closed solid whose ray interval is [tn, tf]: records, in the lanes of `hit`, the
// first of tn and tf inside (tmin, closest t so far) — a ray starting inside hits the exit.
template <class A>
inline void commit_solid_hit(const simd::Floats<A>& tn, const simd::Floats<A>& tf,
                             const RayPacket<A>& r, const simd::Mask<A>& hit, int32_t bits,
                             HitPacket<A>& h) {
  auto near_ok = (tn > r.tmin) & (tn < h.t);
  auto far_ok = (tf > r.tmin) & (tf < h.t);
  commit_hit<A>(simd::select<A>(near_ok, tn, tf), hit & (near_ok | far_ok), bits, h);
}

}  // namespace raylane
