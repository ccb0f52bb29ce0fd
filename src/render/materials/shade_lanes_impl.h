// The body of the lane BSDF (render/materials/shade_lanes.h), instantiated once per instruction set
// by src/render/render_lanes_<isa>.cpp. Include from nowhere else. It is Bsdf
// (src/render/materials/bsdf.cpp) rewritten for lanes: every branch of the scalar code becomes a
// mask, both sides of each are computed and the lane's side is selected, so a NaN or inf on the
// side not taken never reaches a result (selects, never multiplications by a mask).
#pragma once

#include "raylane/render/materials/bsdf_steps.h"
#include "raylane/render/materials/shade_lanes.h"
#include "raylane/simd/lane_lookup.h"
#include "raylane/simd/lane_math.h"
#include "raylane/simd/lane_numbers.h"
#include "raylane/simd/lane_rows.h"
#include "render/materials/microfacet_lanes_impl.h"

namespace raylane::detail {

template <class A>
using F = simd::Floats<A>;
template <class A>
using M = simd::Mask<A>;

using simd::FloatVec3;

template <class A>
F<A> dot(const FloatVec3<A>& a, const FloatVec3<A>& b) {
  return simd::fma(a.x, b.x, simd::fma(a.y, b.y, a.z * b.z));
}
template <class A>
FloatVec3<A> select(const M<A>& m, const FloatVec3<A>& a, const FloatVec3<A>& b) {
  return {simd::select(m, a.x, b.x), simd::select(m, a.y, b.y), simd::select(m, a.z, b.z)};
}
template <class A>
M<A> finite(const F<A>& v) {
  return xsimd::abs(v) <= F<A>(3.40282347e38f);  // false for NaN and ±inf
}

using simd::load3;
using simd::store3;

// f·|cos θi| per channel and the sampling density, as Bsdf::evaluate's BsdfEval.
template <class A>
struct LaneEval {
  F<A> f[3], pdf;
};

// The Phong lobe's Smith G1 (render/materials/bsdf_steps.h), g1_scale = √(α/2 + 1) per material.
template <class A>
F<A> g1(const F<A>& cos_v, const F<A>& cos_vm, const F<A>& g1_scale) {
  return bsdf_steps::rational_smith_g1(cos_v, cos_vm, g1_scale);
}

// One batch of W shading points: the material's columns gathered, and what Bsdf's constructor
// derives from the normal and wo. A batch that takes only diffuse lobes (all_diffuse: no glossy
// or transmission lobe, and every lane's u0 below pd) gathers only what the diffuse lobe reads
// (gathers are the lanes' slowest loads); the other columns are then 0 and unread.
template <class A>
struct LaneBsdf {
  F<A> kd[3], ks[3], pd, pr, pt, alpha, d_scale, pm_scale, g1_scale;
  FloatVec3<A> n, wo;
  F<A> cos_o, eta_o, eta_i;
  // GGX and Beckman lanes (render/materials/microfacet.h), gathered only where the scene has them.
  F<A> microfacet, alpha_g2;
  bool phong_only_ = true;
  M<A> live;  // dot(ns, wo) is finite and not 0 (the scalar Bsdf's black() otherwise)
  bool diffuse_only_, all_diffuse_;

  [[gnu::always_inline]] LaneBsdf(const LaneMaterials& m, const ShadeBatch& b, std::size_t i,
                                  const F<A>& u0) {
    auto idx = simd::load<A>(b.material.data() + i);
    // The materials' columns are short: read by register permutes where they fit (lookup).
    auto gather = [&](const std::vector<float>& col) {
      return simd::lookup<A>(col.data(), m.count, idx, col.size());
    };
    // A textured scene's rows carry their own Kd and lobe probabilities (ShadeBatch::per_row_kd).
    const bool rows = b.per_row_kd;
    auto own_or_gather = [&](const ShadeBatch::Column& own, const std::vector<float>& col) {
      return rows ? simd::load<A>(own.data() + i) : gather(col);
    };
    pd = own_or_gather(b.pd_at, m.pd), pr = own_or_gather(b.pr_at, m.pr);
    pt = own_or_gather(b.pt_at, m.pt);
    // Only the batch's own rows decide: its padding gathers material 0, which may be black or
    // an emitter (pd = 0) and would send every wavefront's last batch the general way.
    const std::size_t left = b.size() - i, W = std::size_t(simd::kWidth<A>);
    const M<A> own = simd::first_lanes<A>(int(left < W ? left : W));
    diffuse_only_ = simd::none<A>(((pr > F<A>(0.0f)) | (pt > F<A>(0.0f))) & own);
    all_diffuse_ = diffuse_only_ && simd::none<A>((!(u0 < pd)) & own);
    for (int k = 0; k < 3; ++k)
      kd[k] = own_or_gather(b.kd_at[k], m.kd[k]), ks[k] = F<A>(0.0f);
    F<A> ior(1.0f);
    alpha = d_scale = pm_scale = g1_scale = F<A>(0.0f);
    if (!all_diffuse_) {
      for (int k = 0; k < 3; ++k)
        ks[k] = gather(m.ks[k]);
      alpha = gather(m.alpha), d_scale = gather(m.d_scale), pm_scale = gather(m.pm_scale);
      g1_scale = gather(m.g1_scale), ior = gather(m.ior);
      phong_only_ = m.all_phong;
      if (!phong_only_) microfacet = gather(m.microfacet), alpha_g2 = gather(m.alpha_g2);
    }
    FloatVec3<A> ns = load3<A>(b.n, i);
    wo = load3<A>(b.wo, i);
    F<A> c = dot(ns, wo);
    M<A> entering = c > F<A>(0.0f);
    n = select(entering, ns, FloatVec3<A>{-ns.x, -ns.y, -ns.z});
    cos_o = xsimd::abs(c);
    eta_o = simd::select(entering, F<A>(1.0f), ior);
    eta_i = simd::select(entering, ior, F<A>(1.0f));
    live = finite<A>(c) & (c != F<A>(0.0f)) & (pd + pr + pt > F<A>(0.0f));
  }

  M<A> refracts(const F<A>& cos_om) const {
    F<A> eta = eta_o / eta_i;
    return F<A>(1.0f) - eta * eta * (F<A>(1.0f) - cos_om * cos_om) >= F<A>(0.0f);
  }

  F<A> cos_power(const FloatVec3<A>& m) const {
    F<A> c = dot(m, n);
    return simd::select(c > F<A>(0.0f), simd::pow_unit<A>(xsimd::max(c, F<A>(0.0f)), alpha),
                        F<A>(0.0f));
  }

  // GGX's and Beckman's D, p(m) and G in their lanes, the Phong values kept in the others.
  void other_microfacets(const FloatVec3<A>& m, const F<A>& cos_i, const F<A>& om, const F<A>& im,
                         F<A>& d, F<A>& pm, F<A>& g) const {
    const M<A> phong = microfacet == F<A>(0.0f), ggx = microfacet == F<A>(1.0f);
    F<A> dm, pmm;
    microfacet_lanes::density<A>(ggx, dot(m, n), alpha_g2, dm, pmm);
    d = simd::select(phong, d, dm), pm = simd::select(phong, pm, pmm);
    F<A> g_ggx = microfacet_lanes::ggx_g1<A>(cos_i, im, alpha_g2) *
                 microfacet_lanes::ggx_g1<A>(cos_o, om, alpha_g2);
    g = simd::select(ggx, g_ggx, g);
  }

  LaneEval<A> evaluate(const FloatVec3<A>& wi) const;
  FloatVec3<A> sample(const F<A>& u0, const F<A>& u1, const F<A>& u2, M<A>& valid) const;

  // No lane has a glossy or a transmission lobe (pr = pt = 0; the course scene's materials are
  // all diffuse): evaluate_diffuse then gives evaluate()'s answers bit for bit, and where every
  // lane also picks its diffuse lobe (u0 < pd), sample_diffuse gives sample()'s. They are the
  // same operations on the side the lanes take, without the other lobes' powers, roots and
  // divisions.
  bool diffuse_only() const { return diffuse_only_; }
  bool all_diffuse() const { return all_diffuse_; }
  LaneEval<A> evaluate_diffuse(const FloatVec3<A>& wi) const;
  FloatVec3<A> sample_diffuse(const F<A>& u1, const F<A>& u2, M<A>& valid) const;
};

template <class A>
LaneEval<A> LaneBsdf<A>::evaluate(const FloatVec3<A>& wi) const {
  const F<A> zero(0.0f), one(1.0f), inv_pi(0.318309886183790671538f);
  F<A> cos_i = dot(wi, n);
  M<A> reflect_side = cos_i > zero;
  // The microfacet normal: the half vector on wo's side, the generalised one (Walter eq. 16)
  // for transmission, turned to n's side.
  FloatVec3<A> h = wi + wo;
  FloatVec3<A> ht = (wo * eta_o + wi * eta_i) * F<A>(-1.0f);
  FloatVec3<A> m = select(reflect_side, h, ht);
  F<A> len = xsimd::sqrt(dot(m, m));
  m = m * (one / len);
  m = select(dot(m, n) < zero, m * F<A>(-1.0f), m);
  F<A> cp = cos_power(m);
  F<A> d = d_scale * cp, pm = pm_scale * cp;
  F<A> om = dot(wo, m), im = dot(wi, m);
  F<A> g = g1<A>(cos_i, im, g1_scale) * g1<A>(cos_o, om, g1_scale);
  if (!phong_only_) other_microfacets(m, cos_i, om, im, d, pm, g);
  F<A> c5 = bsdf_steps::schlick_weight(om);
  M<A> refr = refracts(om);
  // Reflection (Bsdf::evaluate_reflection): diffuse, the reflection lobe with F, and what
  // total internal reflection sends back of the transmission lobe with 1 − F.
  M<A> tir = (pt > zero) & !refr;
  F<A> spec = d * g / (F<A>(4.0f) * cos_o);
  F<A> lobe = simd::select((pm > zero) & (im > zero), pm / (F<A>(4.0f) * im), zero);
  F<A> pdf_r = pd * cos_i * inv_pi + (pr + simd::select(tir, pt, zero)) * lobe;
  // Transmission (Walter eqs. 21 and 17, radiance scaled by η_o²).
  F<A> den = eta_o * om + eta_i * im;
  M<A> transmits = (cos_i < zero) & (pt > zero) & (len > zero) & (om > zero) & (im < zero) & refr &
                   (den != zero);
  F<A> inv_den2 = one / (den * den), abs_im = xsimd::abs(im);
  F<A> st = d * g * abs_im * om * eta_o * eta_o * inv_den2 / cos_o;
  F<A> pdf_t = pt * pm * eta_i * eta_i * abs_im * inv_den2;
  LaneEval<A> out;
  for (int k = 0; k < 3; ++k) {
    F<A> fresnel = ks[k] + (one - ks[k]) * c5;
    F<A> f_r = kd[k] * cos_i * inv_pi + simd::select(pr > zero, fresnel * spec, zero) +
               simd::select(tir, (one - fresnel) * spec, zero);
    F<A> f_t = (one - fresnel) * st;
    out.f[k] = simd::select(live & reflect_side, f_r, simd::select(live & transmits, f_t, zero));
  }
  out.pdf = simd::select(live & reflect_side, pdf_r, simd::select(live & transmits, pdf_t, zero));
  return out;
}

// evaluate() with pr = pt = 0 in every lane: no total internal reflection and no transmission
// (both need pt > 0), so f is the diffuse term plus evaluate()'s two zero terms and the density
// the diffuse one plus (pr + 0)·lobe = +0 (the lobe is finite: a positive density over a
// positive cosine, or 0). The zeros are added as evaluate() adds them (−0 + 0 is +0).
template <class A>
LaneEval<A> LaneBsdf<A>::evaluate_diffuse(const FloatVec3<A>& wi) const {
  const F<A> zero(0.0f), inv_pi(0.318309886183790671538f);
  F<A> cos_i = dot(wi, n);
  M<A> reflected = live & (cos_i > zero);
  LaneEval<A> out;
  for (int k = 0; k < 3; ++k)
    out.f[k] = simd::select(reflected, kd[k] * cos_i * inv_pi + zero + zero, zero);
  out.pdf = simd::select(reflected, pd * cos_i * inv_pi + zero, zero);
  return out;
}

// Bsdf::sample: u0 picks the lobe; (u1, u2) warp a cosine-weighted direction (Malley) or a
// microfacet normal by the course's cos θm = u1^(1/(α+1)) (sampling.h), reflected or refracted.
template <class A>
FloatVec3<A> LaneBsdf<A>::sample(const F<A>& u0, const F<A>& u1, const F<A>& u2,
                                 M<A>& valid) const {
  const F<A> zero(0.0f), one(1.0f);
  simd::LaneSinCos<A> phi = simd::sincos_2pi<A>(u2);
  M<A> diffuse = u0 < pd;
  F<A> cos_m = simd::pow_unit<A>(u1, one / (alpha + one));
  if (!phong_only_)
    cos_m = simd::select(microfacet == F<A>(0.0f), cos_m,
                         microfacet_lanes::sample_cos<A>(microfacet == F<A>(1.0f), u1, alpha_g2));
  F<A> sin_t =
      simd::select(diffuse, xsimd::sqrt(u1), xsimd::sqrt(xsimd::max(zero, one - cos_m * cos_m)));
  F<A> cos_t = simd::select(diffuse, xsimd::sqrt(xsimd::max(zero, one - u1)), cos_m);
  FloatVec3<A> dir = simd::to_world(n, FloatVec3<A>{sin_t * phi.cos, sin_t * phi.sin, cos_t});
  // The glossy lobes: dir is the microfacet normal m.
  F<A> om = dot(wo, dir);
  FloatVec3<A> reflected = dir * (F<A>(2.0f) * om) - wo;
  F<A> eta = eta_o / eta_i;
  F<A> k = one - eta * eta * (one - om * om);
  M<A> refract = (u0 >= pd + pr) & refracts(om);
  FloatVec3<A> refracted = dir * (eta * om - xsimd::sqrt(xsimd::max(k, zero))) - wo * eta;
  M<A> glossy_ok = (om > zero) & ((refract & (dot(refracted, n) < zero)) |
                                  ((!refract) & (dot(reflected, n) > zero)));
  FloatVec3<A> wi = select(diffuse, dir, select(refract, refracted, reflected));
  F<A> len = xsimd::sqrt(dot(wi, wi));
  valid = live & (diffuse | glossy_ok) & (len > zero) & finite<A>(len);
  return wi * (one / len);
}

// sample() where every lane's u0 < pd: the diffuse side of each of its selects.
template <class A>
FloatVec3<A> LaneBsdf<A>::sample_diffuse(const F<A>& u1, const F<A>& u2, M<A>& valid) const {
  const F<A> zero(0.0f), one(1.0f);
  simd::LaneSinCos<A> phi = simd::sincos_2pi<A>(u2);
  F<A> sin_t = xsimd::sqrt(u1), cos_t = xsimd::sqrt(xsimd::max(zero, one - u1));
  FloatVec3<A> wi = simd::to_world(n, FloatVec3<A>{sin_t * phi.cos, sin_t * phi.sin, cos_t});
  F<A> len = xsimd::sqrt(dot(wi, wi));
  valid = live & (len > zero) & finite<A>(len);
  return wi * (one / len);
}

// What the BSDF answers for rows [i, i + W): its sample (direction, f·|cos θi| and density, all
// 0 where there is none) and its evaluation toward the row's light direction.
template <class A>
struct BsdfAnswers {
  FloatVec3<A> wi;
  F<A> value[3], pdf;
  F<A> light_f[3], light_pdf;
};

template <class A>
BsdfAnswers<A> bsdf_answers(const LaneMaterials& materials, const ShadeBatch& b, std::size_t i) {
  M<A> valid;
  const F<A> u0 = simd::load<A>(b.u_lobe.data() + i), u1 = simd::load<A>(b.u1.data() + i),
             u2 = simd::load<A>(b.u2.data() + i);
  LaneBsdf<A> bsdf(materials, b, i, u0);
  const bool diffuse = bsdf.diffuse_only();
  BsdfAnswers<A> out;
  out.wi = bsdf.all_diffuse() ? bsdf.sample_diffuse(u1, u2, valid) : bsdf.sample(u0, u1, u2, valid);
  auto evaluate = [&](const FloatVec3<A>& w) {
    return diffuse ? bsdf.evaluate_diffuse(w) : bsdf.evaluate(w);
  };
  const LaneEval<A> e = evaluate(out.wi);
  valid = valid & (e.pdf > F<A>(0.0f)) & finite<A>(e.pdf);
  for (int k = 0; k < 3; ++k)
    out.value[k] = simd::select(valid, e.f[k], F<A>(0.0f));
  out.pdf = simd::select(valid, e.pdf, F<A>(0.0f));
  const LaneEval<A> l = evaluate(load3<A>(b.light_wi, i));
  for (int k = 0; k < 3; ++k)
    out.light_f[k] = l.f[k];
  out.light_pdf = l.pdf;
  return out;
}

template <class A>
void shade_lanes_range(const LaneMaterials& materials, ShadeBatch& b) {
  constexpr std::size_t W = simd::kWidth<A>;
  for (std::size_t i = 0; i < b.size(); i += W) {
    const BsdfAnswers<A> a = bsdf_answers<A>(materials, b, i);
    store3<A>(b.wi, i, a.wi);
    for (int k = 0; k < 3; ++k) {
      simd::store<A>(b.value[k].data() + i, a.value[k]);
      simd::store<A>(b.light_f[k].data() + i, a.light_f[k]);
    }
    simd::store<A>(b.pdf.data() + i, a.pdf);
    simd::store<A>(b.light_pdf.data() + i, a.light_pdf);
  }
}

}  // namespace raylane::detail
