// Ray and hit packets: W rays in SIMD lanes, structure of arrays (design.md, "Packets").
// Templates over the instruction set A; used only inside the per-ISA translation units.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

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

// How a kernel walks the rows [begin, end) of one run of its table. Two layouts share every
// kernel's source:
// - LanesAreRays (packet traversal): each lane is a ray; each step broadcasts one row.
// - LanesAreRows (single-ray traversal): every lane holds the same ray; each step loads W
//   consecutive rows, one per lane. The tables are SoA and a run's rows are contiguous, so
//   that is one load per column (design.md, "Data layout").
template <class A>
struct LanesAreRays {
  static constexpr bool kOneRay = false;
  uint32_t i, end;
  simd::Mask<A> lanes;  // the rays to test

  bool more() const { return i < end; }
  void next() { ++i; }
  simd::Mask<A> mask() const { return lanes; }
  simd::Floats<A> col(const std::vector<float>& c) const { return simd::Floats<A>(c[i]); }
  simd::Ints<A> bits(PrimTag tag) const { return simd::Ints<A>(prim_bits(tag, i)); }
};

template <class A>
struct LanesAreRows {
  static constexpr bool kOneRay = true;
  static constexpr int W = simd::kWidth<A>;
  uint32_t i, end;    // no lane mask: a single ray is traced only while it is live
  std::size_t table;  // rows in the table

  bool more() const { return i < end; }
  void next() { i += W; }
  simd::Mask<A> mask() const { return simd::first_lanes<A>(int(std::min<uint32_t>(end - i, W))); }
  // Rows i … i + W − 1; near the table's end (the last rows, or a small table) only the rows
  // that exist are read.
  simd::Floats<A> col(const std::vector<float>& c) const {
    if (i + W <= table) return simd::load<A>(c.data() + i);
    return simd::load_first<A>(c.data() + i, int(table - i));
  }
  simd::Ints<A> bits(PrimTag tag) const {
    return simd::Ints<A>(prim_bits(tag, i)) + simd::lane_index<A>();
  }
};

// Records hit distance t as primitive `bits` in the lanes of `ok`.
template <class A>
inline void commit_hit(const simd::Floats<A>& t, const simd::Mask<A>& ok, const simd::Ints<A>& bits,
                       HitPacket<A>& h) {
  h.t = simd::select<A>(ok, t, h.t);
  h.prim = simd::select<A>(ok, bits, h.prim);
  h.found = h.found | ok;
}

// For a closed solid whose ray interval is [tn, tf]: records, in the lanes of `hit`, the
// first of tn and tf inside (tmin, closest t so far) — a ray starting inside hits the exit.
template <class A>
inline void commit_solid_hit(const simd::Floats<A>& tn, const simd::Floats<A>& tf,
                             const RayPacket<A>& r, const simd::Mask<A>& hit,
                             const simd::Ints<A>& bits, HitPacket<A>& h) {
  auto near_ok = (tn > r.tmin) & (tn < h.t);
  auto far_ok = (tf > r.tmin) & (tf < h.t);
  commit_hit<A>(simd::select<A>(near_ok, tn, tf), hit & (near_ok | far_ok), bits, h);
}

}  // namespace raylane
