// sample_cones (render/lights/light_lanes.h) in double lanes, instantiated per instruction set by
// src/render/render_lanes_<isa>.cpp. Include from nowhere else. Each step is the scalar
// code's (Sphere::sample_subtended, cone_one_minus_cos, sample_uniform_cone, sincos_2pi and
// Frame), in the same order, so the two differ only where the compiler fuses a multiply-add.
#pragma once

#include "raylane/core/fast_math.h"
#include "raylane/render/lights/light_lanes.h"
#include "raylane/simd/lanes.h"

namespace raylane::detail {

template <class A>
using Doubles = xsimd::batch<double, A>;

using simd::DoubleVec3;

template <class A>
DoubleVec3<A> load3(const std::array<std::vector<double>, 3>& c, std::size_t i) {
  return {Doubles<A>::load_unaligned(c[0].data() + i), Doubles<A>::load_unaligned(c[1].data() + i),
          Doubles<A>::load_unaligned(c[2].data() + i)};
}

template <class A>
void store3(std::array<std::vector<double>, 3>& c, std::size_t i, const DoubleVec3<A>& v) {
  v.x.store_unaligned(c[0].data() + i);
  v.y.store_unaligned(c[1].data() + i);
  v.z.store_unaligned(c[2].data() + i);
}

// sincos_2pi (core/fast_math.h): the turn reduced exactly to a quarter q and |r| ≤ 1/8, then
// the quarter's rotation chosen per lane.
template <class A>
void sincos_2pi_lanes(const Doubles<A>& u, Doubles<A>& sin_out, Doubles<A>& cos_out) {
  using D = Doubles<A>;
  constexpr double kTwoPi = 6.283185307179586476925;
  D q = xsimd::nearbyint(D(4.0) * u);
  D a = D(kTwoPi) * (u - D(0.25) * q);
  D s = fast_math_detail::sin_poly(a), c = fast_math_detail::cos_poly(a);
  D quarter = q - D(4.0) * xsimd::floor(q * D(0.25));  // q mod 4, exact
  auto q1 = quarter == D(1.0), q2 = quarter == D(2.0), q3 = quarter == D(3.0);
  // simd::negate: at u = 1/4, 1/2, 3/4 a component is a zero whose sign must be the scalar's.
  const D minus_s = simd::negate(s), minus_c = simd::negate(c);
  sin_out = xsimd::select(q1, c, xsimd::select(q2, minus_s, xsimd::select(q3, minus_c, s)));
  cos_out = xsimd::select(q1, minus_s, xsimd::select(q2, minus_c, xsimd::select(q3, s, c)));
}

// The sphere of rows [i, i + W): the batch's columns, or every_row's broadcast.
template <class A>
struct ConeSphereLanes {
  DoubleVec3<A> center;
  Doubles<A> radius, choice;
  ConeSphereLanes(const ConeBatch& b, const ConeSphere* every_row, std::size_t i) {
    using D = Doubles<A>;
    if (every_row) {
      const ConeSphere& s = *every_row;
      center = {D(s.center[0]), D(s.center[1]), D(s.center[2])};
      radius = D(s.radius), choice = D(s.choice);
      return;
    }
    center = load3<A>(b.center, i);
    radius = D::load_unaligned(b.radius.data() + i);
    choice = D::load_unaligned(b.choice.data() + i);
  }
};

// ConeBatch::wi_float for rows [i, i + W): wi where pdf > 0 in a row below the batch's size,
// else 0 (a padding row's sphere may be any, so its direction is not written).
template <class A>
void store_wi_float(const ConeBatch& b, std::size_t i, const DoubleVec3<A>& wi,
                    const Doubles<A>& pdf) {
  using D = Doubles<A>;
  alignas(64) static constexpr double kRow[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const auto keep = (pdf > D(0.0)) & (D::load_aligned(kRow) + D(double(i)) < D(double(b.size())));
  simd::store_narrowed<A>(b.wi_float[0] + i, xsimd::select(keep, wi.x, D(0.0)));
  simd::store_narrowed<A>(b.wi_float[1] + i, xsimd::select(keep, wi.y, D(0.0)));
  simd::store_narrowed<A>(b.wi_float[2] + i, xsimd::select(keep, wi.z, D(0.0)));
}

template <class A>
void sample_cones_range(ConeBatch& b, const ConeSphere* every_row) {
  using D = Doubles<A>;
  constexpr std::size_t W = D::size;
  const D zero(0.0), one(1.0);
  for (std::size_t i = 0; i < b.size(); i += W) {
    const ConeSphereLanes<A> sphere(b, every_row, i);
    DoubleVec3<A> ref = load3<A>(b.ref, i), c = sphere.center;
    D r = sphere.radius;
    DoubleVec3<A> w{c.x - ref.x, c.y - ref.y, c.z - ref.z};
    D r2 = r * r, d2 = w.x * w.x + w.y * w.y + w.z * w.z;
    auto outside = d2 > r2;
    D d = xsimd::sqrt(d2);
    // cone_one_minus_cos: sin²θmax / (1 + cos θmax), no cancellation for narrow cones.
    D sin2_max = r2 / d2;
    D omc_max = sin2_max / (one + xsimd::sqrt(xsimd::max(zero, one - sin2_max)));
    // sample_uniform_cone.
    D omc = D::load_unaligned(b.u1.data() + i) * omc_max;
    D cos_t = one - omc;
    D sin_t = xsimd::sqrt(xsimd::max(zero, omc * (D(2.0) - omc)));
    D sin_phi, cos_phi;
    sincos_2pi_lanes<A>(D::load_unaligned(b.u2.data() + i), sin_phi, cos_phi);
    DoubleVec3<A> local{sin_t * cos_phi, sin_t * sin_phi, cos_t};
    // The nearer root of the ray from ref along the sampled direction.
    D sin2 = local.x * local.x + local.y * local.y;
    D t_hit = d * local.z - xsimd::sqrt(xsimd::max(zero, r2 - d2 * sin2));
    DoubleVec3<A> axis{w.x / d, w.y / d, w.z / d};
    const DoubleVec3<A> wi = simd::to_world(axis, local);
    store3<A>(b.wi, i, wi);
    t_hit.store_unaligned(b.dist.data() + i);
    constexpr double kTwoPi = 6.283185307179586476925;
    D solid_angle = xsimd::select(outside, D(kTwoPi) * omc_max, zero);
    solid_angle.store_unaligned(b.solid_angle.data() + i);
    const D pdf = xsimd::select(solid_angle > zero, sphere.choice / solid_angle, zero);
    pdf.store_unaligned(b.pdf.data() + i);
    if (b.wi_float[0]) store_wi_float<A>(b, i, wi, pdf);
  }
}

}  // namespace raylane::detail
