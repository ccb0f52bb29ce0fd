// sort_arrival_rows (render/arrival_lanes.h) in lanes, instantiated per instruction set by
// src/render/render_lanes_<isa>.cpp. Include from nowhere else. Its answers are arrival_of's,
// ray by ray (tests/render/arrival_lanes_test.cpp).
#pragma once

#include <algorithm>

#include "raylane/render/arrival_lanes.h"
#include "raylane/simd/lane_convert.h"
#include "raylane/simd/lane_lookup.h"
#include "raylane/simd/lane_rows.h"
#include "raylane/simd/lane_u64.h"
#include "raylane/simd/lanes.h"

namespace raylane::detail {

// The lane rows' seeds and survival (row_path_columns_of's steps) in lanes: the seeds a
// register of 64-bit lanes at a time, gathered from the paths (simd::gather_u64) and salted in
// simd::U64Lanes; the survival a select on the depth in float lanes. GCC left the plain loop
// scalar. The rows after the last whole register take the reference's steps.
template <class A>
bool row_path_columns_range(const ArrivalColumns& in, const ArrivalRows& out, std::size_t n) {
  using U64 = simd::U64Lanes<A>;
  using I = simd::Ints<A>;
  using F = simd::Floats<A>;
  constexpr std::size_t N = U64::V::size, W = std::size_t(simd::kWidth<A>);
  const U64 base(in.light_salt), step(in.salt_step), offset(in.bsdf_offset);
  std::size_t r = 0;
  for (; r + N <= n; r += N) {
    const U64 seed = simd::gather_u64<A>(in.pixel_seed, out.path + r, in.seed_stride);
    const U64 light = base + simd::load_widened<A>(out.depth + r) * step;
    (seed ^ light).v.store_unaligned(out.light_seed + r);
    (seed ^ (light + offset)).v.store_unaligned(out.bsdf_seed + r);
  }
  for (; r < n; ++r)  // the reference's steps (its survival written again below)
    row_path_columns_of(in, out, r);
  // Depths below 2^31 (ArrivalColumns): a signed compare is the unsigned one.
  const I first = I(int32_t(in.roulette_from) - 1);
  const F with(in.survival), without(1.0f);
  uint32_t any = 0;
  std::size_t i = 0;
  for (; i + W <= n; i += W) {
    const simd::Mask<A> on =
        xsimd::bool_cast(simd::load<A>(reinterpret_cast<const int32_t*>(out.depth + i)) > first);
    simd::store<A>(out.survival + i, simd::select<A>(on, with, without));
    any |= simd::bits<A>(on);
  }
  for (; i < n; ++i) {
    const bool roulette = out.depth[i] >= in.roulette_from;
    out.survival[i] = roulette ? in.survival : 1.0f;
    any |= roulette ? 1u : 0u;
  }
  return any != 0;
}

template <class A>
void sort_arrival_rows_range(const ArrivalColumns& in, ArrivalRows& out) {
  using I = simd::Ints<A>;
  using F = simd::Floats<A>;
  constexpr int W = simd::kWidth<A>;
  auto ints = [](const F& v) { return xsimd::bitwise_cast<I>(v); };
  // Integer columns read as floats, by permutes where they are short (a scene's handful of
  // boxes and materials) or gathers: both move bits, neither converts them.
  auto read = [&](const uint32_t* col, std::size_t n, const I& idx) {
    return ints(simd::lookup<A>(reinterpret_cast<const float*>(col), n, idx));
  };
  auto load_rows = [&](const uint32_t* col, std::size_t k, int m) {
    const float* at = reinterpret_cast<const float*>(col + k);
    return ints(m == W ? simd::load<A>(at) : simd::load_first<A>(at, m));
  };
  // The kinds a hit can have (their tables have rows), listed once.
  std::array<int32_t, kPrimKindCount> tags{};
  std::size_t kinds = 0;
  for (std::size_t t = 0; t < kPrimKindCount; ++t)
    if (in.material_of[t] != nullptr) tags[kinds++] = int32_t(t);
  const I invalid = I(int32_t(PrimRef::kInvalidBits));
  const I row_mask = I(int32_t(PrimRef::kMaxRows - 1));
  const I emitter = I(int32_t(in.emitter_route)), lanes_route = I(int32_t(in.lanes_route));
  const I max_depth = I(int32_t(in.max_depth));
  // A batch's throughputs as float lanes: the last batch's through a copy (the columns end at
  // the count).
  auto beta_lanes = [&](int c, std::size_t k, int m) {
    if (m == W) return simd::load_narrowed<A>(in.beta[std::size_t(c)] + k);
    alignas(64) double part[W] = {};
    std::copy_n(in.beta[std::size_t(c)] + k, m, part);
    return simd::load_narrowed<A>(part);
  };
  const uint32_t escapes_seen = in.environment ? ~0u : 0u;
  std::size_t lanes = 0, rare = 0;
  for (std::size_t k = 0; k < in.count; k += W) {
    const int m = int(std::min<std::size_t>(W, in.count - k));
    const uint32_t own = (1u << m) - 1;  // m ≤ 16
    const I prim = load_rows(in.prim, k, m), path = load_rows(in.ray_path, k, m);
    const uint32_t missed = simd::bits<A>(simd::equal<A>(prim, invalid)) & own;
    const uint32_t hit = own & ~missed;
    // The material: each kind present from its own column, at row 0 in the other lanes (a
    // kind with hits has a row 0).
    const I tag = (prim >> PrimRef::kRowBits) & I((1 << PrimRef::kTagBits) - 1);
    const I row = prim & row_mask;
    I material(0);
    for (std::size_t j = 0; j < kinds; ++j) {
      const simd::Mask<A> on = simd::equal<A>(tag, I(tags[j]));
      if ((simd::bits<A>(on) & hit) == 0) continue;
      const I rows = simd::select<A>(on, row, I(0));
      const std::size_t t = std::size_t(tags[j]);
      material = simd::select<A>(on, read(in.material_of[t], in.rows_of[t], rows), material);
    }
    const I route = read(in.route, in.materials, material);
    const I depth = load_rows(in.depth, k, m);
    const uint32_t to_emitter = simd::bits<A>(simd::equal<A>(route, emitter)) & hit;
    const uint32_t goes_on = simd::bits<A>(xsimd::bool_cast(depth < max_depth)) & hit;
    const uint32_t in_lanes =
        simd::bits<A>(simd::equal<A>(route, lanes_route)) & goes_on & ~to_emitter;
    const uint32_t to_rare =
        (missed & escapes_seen) | to_emitter | (goes_on & ~to_emitter & ~in_lanes);
    const I ray = I(int32_t(k)) + simd::lane_index<A>();
    if (in_lanes != 0) {  // never with the double shading, whose call passes no columns
      const simd::LanePacker<A> vertex(in_lanes);
      vertex.store(out.path + lanes, path), vertex.store(out.ray + lanes, ray);
      vertex.store(out.material + lanes, material), vertex.store(out.depth + lanes, depth);
      for (int c = 0; c < 3; ++c)
        vertex.store(out.beta[std::size_t(c)] + lanes, beta_lanes(c, k, m));
      lanes += std::size_t(vertex.count());
    }
    if (to_rare != 0) {
      const simd::LanePacker<A> other(to_rare);
      other.store(out.rare + rare, ray);
      rare += std::size_t(other.count());
    }
  }
  out.lanes = lanes, out.rare_count = rare;
  if (in.pixel_seed != nullptr) out.any_roulette = row_path_columns_range<A>(in, out, lanes);
}

}  // namespace raylane::detail
