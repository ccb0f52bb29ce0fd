// Ray and hit packets: W rays in SIMD lanes, structure of arrays (docs/design.md, "Packets").
// Templates over the instruction set A; used only inside the per-ISA translation units.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "raylane/core/prim_ref.h"
#include "raylane/simd/lanes.h"

namespace raylane {

// The ray's frame for the watertight triangle test, computed once per ray as Woop, Benthin
// and Wald (2013, JCGT 2(1), §3) prescribe: the axis of largest |d| becomes z (ties to the
// lowest axis), x and y follow cyclically and are swapped when d_z < 0 to keep the winding;
// the shear (sx, sy, sz) maps d to +z. Per lane, as masks naming the world axis each sheared
// axis reads; and, when every active lane has the same permutation (coherent packets, and
// always for a single ray in every lane), that permutation, so a kernel can load permuted
// columns instead of selecting in every lane.
template <class A>
struct RayShear {
  using F = simd::Floats<A>;
  simd::Mask<A> x_is[3], y_is[3], z_is[3];
  F sx, sy, sz;
  bool uniform = false;  // every active lane has the axes (kx, ky, kz)
  int kx = 0, ky = 1, kz = 2;

  static F pick(const simd::Mask<A>* is, const F& x, const F& y, const F& z) {
    return simd::select<A>(is[0], x, simd::select<A>(is[1], y, z));
  }

  // Set in place (set, set_unused) by the packet's set-up: assigning a constructed frame copied
  // its few hundred bytes per packet (a rep movs in the profile).
  RayShear() = default;
  // The frame of packets that meet no triangle (a scene without any): axes (0, 1, 2) in every
  // lane and no shear, for a division and some thirty selects less per packet. Only triangles
  // read a frame; the hand-over to single rays copies it along.
  void set_unused() {
    const simd::Mask<A> yes = F(0.0f) == F(0.0f), no = !yes;
    for (int k = 0; k < 3; ++k)
      x_is[k] = k == 0 ? yes : no, y_is[k] = k == 1 ? yes : no, z_is[k] = k == 2 ? yes : no;
    sx = F(0.0f), sy = F(0.0f), sz = F(1.0f);
    uniform = true;
    kx = 0, ky = 1, kz = 2;
  }
  void set(const F& dx, const F& dy, const F& dz, const simd::Mask<A>& active) {
    kx = 0, ky = 1, kz = 2;
    F ax = xsimd::abs(dx), ay = xsimd::abs(dy), az = xsimd::abs(dz);
    z_is[0] = (ax >= ay) & (ax >= az);
    z_is[1] = (!z_is[0]) & (ay >= az);
    z_is[2] = (!z_is[0]) & (!z_is[1]);
    // kx = kz + 1, ky = kz + 2 (mod 3); swapped when d[kz] < 0.
    simd::Mask<A> kx_base[3] = {z_is[2], z_is[0], z_is[1]};
    simd::Mask<A> ky_base[3] = {z_is[1], z_is[2], z_is[0]};
    F d_z = pick(z_is, dx, dy, dz);
    auto flip = d_z < F(0.0f);
    for (int k = 0; k < 3; ++k) {
      x_is[k] = (kx_base[k] & (!flip)) | (ky_base[k] & flip);
      y_is[k] = (ky_base[k] & (!flip)) | (kx_base[k] & flip);
    }
    sz = F(1.0f) / d_z;
    sx = pick(x_is, dx, dy, dz) * sz;
    sy = pick(y_is, dx, dy, dz) * sz;
    find_common_axes(simd::bits<A>(active), simd::bits<A>(flip));
  }

 private:
  void find_common_axes(uint32_t act, uint32_t flip) {
    auto same = [act](uint32_t m) { return (m & act) == 0 || (m & act) == act; };
    uniform = same(simd::bits<A>(z_is[0])) && same(simd::bits<A>(z_is[1])) && same(flip);
    if (!uniform || act == 0) return;
    uint32_t lane = 1u << __builtin_ctz(act);
    kz = (simd::bits<A>(z_is[0]) & lane) ? 0 : (simd::bits<A>(z_is[1]) & lane) ? 1 : 2;
    kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (flip & lane) std::swap(kx, ky);
  }
};

// Which plane of each slab a ray meets first: the box's hi where 1/d < 0 (the sign of d,
// even for ±0: docs/hard-cases.md B3), its lo otherwise. Per lane, and as one choice per axis when
// every active lane agrees (coherent packets, single rays), so that a box test can load its
// near and far planes instead of selecting them in every lane.
template <class A>
struct SlabSides {
  using F = simd::Floats<A>;
  simd::Mask<A> hi_first[3];
  uint32_t hi_first_bits[3] = {0, 0, 0};  // the same, lane i as bit i
  bool uniform = false;  // every active lane agrees on each axis: its hi is near iff near_hi[k]
  bool near_hi[3] = {false, false, false};

  // Set in place, member by member: built as a temporary and assigned, GCC 12 copied it through
  // the stack in 16-byte halves, a stall on every packet's setup.
  [[gnu::always_inline]] inline void set(const F& inv_dx, const F& inv_dy, const F& inv_dz,
                                         const simd::Mask<A>& active) {
    const F* inv[3] = {&inv_dx, &inv_dy, &inv_dz};
    uint32_t act = simd::bits<A>(active);
    bool all_agree = true;
    for (int k = 0; k < 3; ++k) {
      hi_first[k] = *inv[k] < F(0.0f);
      hi_first_bits[k] = simd::bits<A>(hi_first[k]);
      uint32_t m = hi_first_bits[k] & act;
      all_agree = all_agree && (m == 0 || m == act);
      near_hi[k] = m != 0;
    }
    uniform = all_agree;
  }
};

template <class A>
struct RayPacket {
  using F = simd::Floats<A>;
  F ox, oy, oz;
  F dx, dy, dz;
  F inv_dx, inv_dy, inv_dz;  // 1/d: ±inf for a ±0 component, signed like d (docs/hard-cases.md B3)
  F tmin;
  F time;  // each lane's instant in the shutter interval (core/ray.h); read by moving kinds only
  // Occlusion: the primitive each lane is aimed at, whose hit shortens the segment instead of
  // blocking it (RayStream::aim); PrimRef::kInvalidBits for none. Unread by closest hit.
  simd::Ints<A> aim;
  simd::Mask<A> active;  // lanes that hold a valid ray still being traced
  // Set with `active`, from the lanes valid then. `active` only ever loses lanes (any-hit
  // traversal retires the lanes that found a hit), so what held for every active lane then
  // holds for every active lane later.
  RayShear<A> shear;
  SlabSides<A> sides;
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
//   that is one load per column (docs/design.md, "Data layout").
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
