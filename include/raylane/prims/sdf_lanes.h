// Signed-distance blocks' program in float lanes: the leaves' distances and the operators, one
// point per lane (sdf_program.h has the same in one number type, for the double reference).
// Lane code: included only through sdf_packet.h.
//
// The leaves are Quilez's exact distances ("distance functions", iquilezles.org), written here
// in forms that round little in float and differ from the reference's where that helps: the
// box as max(lo − p, p − hi) per axis, which never rounds a centre or a half extent; the
// cylinder's height measured from its base. Each distance is a few roundings of coordinates of
// size at most |p| + |leaf|, far below the march's floor of 8 ulps (sdf.h, sdf_tolerance).
// Extrema by simd::max_keep/min_keep (lanes.h: one instruction; xsimd's AVX-512 max and sqrt trip
// GCC 12's -Wuninitialized); their NaN rule is moot, a NaN distance ends a march.
#pragma once

#include <cstdint>

#include "raylane/prims/sdf.h"
#include "raylane/simd/lanes.h"

namespace raylane::detail {

// One leaf's parameters, read from its kind's columns once per block (not once per step).
struct SdfLeafParams {
  uint32_t kind;
  float c[3];  // sphere/torus centre, box lo, cylinder base
  float u[3];  // box hi, cylinder/torus unit axis
  float a, b;  // sphere r; cylinder height h and r; torus R and r
};

inline SdfLeafParams sdf_leaf_params(const SdfTable& s, uint32_t leaf) {
  const uint32_t i = s.leaf_row[leaf];
  SdfLeafParams l{s.leaf_kind[leaf], {}, {}, 0, 0};
  switch (l.kind) {
    case kSdfSphere:
      l.c[0] = s.spheres.cx[i], l.c[1] = s.spheres.cy[i], l.c[2] = s.spheres.cz[i];
      l.a = s.spheres.r[i];
      break;
    case kSdfBox:
      l.c[0] = s.boxes.lox[i], l.c[1] = s.boxes.loy[i], l.c[2] = s.boxes.loz[i];
      l.u[0] = s.boxes.hix[i], l.u[1] = s.boxes.hiy[i], l.u[2] = s.boxes.hiz[i];
      break;
    case kSdfCylinder: {
      const CylinderTable& c = s.cylinders;
      l.c[0] = c.bx[i], l.c[1] = c.by[i], l.c[2] = c.bz[i];
      l.u[0] = c.ux[i], l.u[1] = c.uy[i], l.u[2] = c.uz[i];
      l.a = c.h[i], l.b = c.r[i];
      break;
    }
    default: {
      const TorusColumns& t = s.tori;
      l.c[0] = t.cx[i], l.c[1] = t.cy[i], l.c[2] = t.cz[i];
      l.u[0] = t.ux[i], l.u[1] = t.uy[i], l.u[2] = t.uz[i];
      l.a = t.R[i], l.b = t.r[i];
    }
  }
  return l;
}

template <class A>
inline simd::Floats<A> sdf_length_lanes(const simd::Floats<A>& x, const simd::Floats<A>& y,
                                        const simd::Floats<A>& z) {
  return simd::sqrt<A>(x * x + y * y + z * z);
}

// The distance from the axis through `base` along u and the height along it from `base` (the
// radial part as |f × u|, which does not cancel near the axis: sdf_program.h, sdf_axial).
template <class A>
inline void sdf_axial_lanes(const SdfLeafParams& l, const simd::FloatVec3<A>& p,
                            simd::Floats<A>& radial, simd::Floats<A>& height) {
  using F = simd::Floats<A>;
  const F ux(l.u[0]), uy(l.u[1]), uz(l.u[2]);
  F fx = p.x - F(l.c[0]), fy = p.y - F(l.c[1]), fz = p.z - F(l.c[2]);
  height = fx * ux + fy * uy + fz * uz;
  radial = sdf_length_lanes<A>(fy * uz - fz * uy, fz * ux - fx * uz, fx * uy - fy * ux);
}

template <class A>
inline simd::Floats<A> sdf_leaf_lanes(const SdfLeafParams& l, const simd::FloatVec3<A>& p) {
  using F = simd::Floats<A>;
  const F zero(0.0f);
  switch (l.kind) {
    case kSdfSphere:
      return sdf_length_lanes<A>(p.x - F(l.c[0]), p.y - F(l.c[1]), p.z - F(l.c[2])) - F(l.a);
    case kSdfBox: {
      F qx = simd::max_keep<A>(F(l.c[0]) - p.x, p.x - F(l.u[0]));
      F qy = simd::max_keep<A>(F(l.c[1]) - p.y, p.y - F(l.u[1]));
      F qz = simd::max_keep<A>(F(l.c[2]) - p.z, p.z - F(l.u[2]));
      F inside = simd::min_keep<A>(simd::max_keep<A>(qx, simd::max_keep<A>(qy, qz)), zero);
      return sdf_length_lanes<A>(simd::max_keep<A>(qx, zero), simd::max_keep<A>(qy, zero),
                                 simd::max_keep<A>(qz, zero)) +
             inside;
    }
    case kSdfCylinder: {
      F x, y;
      sdf_axial_lanes<A>(l, p, x, y);
      const F hh(0.5f * l.a);
      F dx = x - F(l.b), dy = xsimd::abs(y - hh) - hh;
      F ox = simd::max_keep<A>(dx, zero), oy = simd::max_keep<A>(dy, zero);
      return simd::min_keep<A>(simd::max_keep<A>(dx, dy), zero) + simd::sqrt<A>(ox * ox + oy * oy);
    }
    default: {
      F x, y;
      sdf_axial_lanes<A>(l, p, x, y);
      F dx = x - F(l.a);
      return simd::sqrt<A>(dx * dx + y * y) - F(l.b);
    }
  }
}

// Quilez's polynomial smooth minimum of width k (sdf_program.h, sdf_smin).
template <class A>
inline simd::Floats<A> sdf_smin_lanes(const simd::Floats<A>& a, const simd::Floats<A>& b, float k) {
  using F = simd::Floats<A>;
  F h = simd::max_keep<A>(F(k) - xsimd::abs(a - b), F(0.0f)) * F(1.0f / k);
  return simd::min_keep<A>(a, b) - h * h * F(0.25f * k);
}

template <class A>
inline simd::Floats<A> sdf_combine_lanes(uint32_t code, const simd::Floats<A>& a,
                                         const simd::Floats<A>& b, float k) {
  switch (code) {
    case kSdfUnion:
      return simd::min_keep<A>(a, b);
    case kSdfIntersect:
      return simd::max_keep<A>(a, b);
    case kSdfDifference:
      return simd::max_keep<A>(a, -b);
    case kSdfSmoothUnion:
      return sdf_smin_lanes<A>(a, b, k);
    case kSdfSmoothIntersect:
      return -sdf_smin_lanes<A>(-a, -b, k);
    default:
      return -sdf_smin_lanes<A>(-a, b, k);
  }
}

// One block ready to be evaluated: its leaves' parameters and its program.
struct SdfBlockLanes {
  SdfLeafParams leaves[kSdfMaxLeaves];
  const uint32_t* program;
  const float* k;
  uint32_t leaf_count, program_count, first_leaf;

  SdfBlockLanes(const SdfTable& s, uint32_t block)
      : program(s.program.data() + s.program_begin[block]),
        k(s.program_k.data() + s.program_begin[block]),
        leaf_count(s.leaf_count[block]),
        program_count(s.program_count[block]),
        first_leaf(s.leaf_begin[block]) {
    for (uint32_t i = 0; i < leaf_count; ++i)
      leaves[i] = sdf_leaf_params(s, first_leaf + i);
  }

  // The block's signed distance at p, per lane.
  template <class A>
  simd::Floats<A> distance(const simd::FloatVec3<A>& p) const {
    simd::Floats<A> stack[kSdfMaxLeaves];
    int top = 0;
    for (uint32_t j = 0; j < program_count; ++j) {
      const uint32_t code = program[j];
      if (code < kSdfMaxLeaves) {
        stack[top++] = sdf_leaf_lanes<A>(leaves[code], p);
        continue;
      }
      --top;
      stack[top - 1] = sdf_combine_lanes<A>(code, stack[top - 1], stack[top], k[j]);
    }
    return stack[0];
  }

  // The leaf nearest p (the least |distance|, the earlier on ties), as its index in the table.
  template <class A>
  simd::Ints<A> nearest_leaf(const simd::FloatVec3<A>& p) const {
    using F = simd::Floats<A>;
    F best(std::numeric_limits<float>::infinity());
    auto leaf = simd::Ints<A>(int32_t(first_leaf));
    for (uint32_t i = 0; i < leaf_count; ++i) {
      F d = xsimd::abs(sdf_leaf_lanes<A>(leaves[i], p));
      simd::Mask<A> nearer = d < best;
      best = simd::select<A>(nearer, d, best);
      leaf = simd::select<A>(nearer, simd::Ints<A>(int32_t(first_leaf + i)), leaf);
    }
    return leaf;
  }
};

}  // namespace raylane::detail
