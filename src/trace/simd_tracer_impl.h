// The body of the SIMD tracer, instantiated once per instruction set by
// src/trace/simd_tracer_*.cpp. Include from nowhere else.
#pragma once

#include <cfloat>
#include <numeric>

#include "raylane/core/ray_offset.h"
#include "raylane/simd/lane_convert.h"
#include "raylane/simd/lane_lookup.h"
#include "raylane/simd/lane_rows.h"
#include "raylane/trace/packet_traverse.h"
#include "raylane/trace/ray_traverse.h"
#include "raylane/trace/simd_tracer.h"
#include "raylane/trace/single_ray.h"
#include "raylane/trace/wide_packet_traverse.h"
#include "trace/float_surfaces_impl.h"

namespace raylane::detail {

// 1/d, and the active mask: the lanes of `loaded` whose ray is valid — finite origin and
// direction (|x| <= FLT_MAX is false for NaN and inf), a non-zero direction, and
// tmin <= tmax (false for NaN); then the rays' shear frame for triangles (where the scene has
// some: `shear`) and the near side of each slab.
template <class A>
void set_reciprocal_and_validity(RayPacket<A>& r, const simd::Floats<A>& tmax,
                                 const simd::Mask<A>& loaded, bool shear) {
  using F = simd::Floats<A>;
  const F one(1.0f), big(FLT_MAX);
  r.inv_dx = one / r.dx, r.inv_dy = one / r.dy, r.inv_dz = one / r.dz;
  auto finite = [&](const F& v) { return xsimd::abs(v) <= big; };
  F dd = r.dx * r.dx + r.dy * r.dy + r.dz * r.dz;
  r.active = loaded & finite(r.ox) & finite(r.oy) & finite(r.oz) & finite(r.dx) & finite(r.dy) &
             finite(r.dz) & (dd > F(0.0f)) & (r.tmin <= tmax);
  if (shear) {
    r.shear.set(r.dx, r.dy, r.dz, r.active);
  } else {
    r.shear.set_unused();
  }
  r.sides.set(r.inv_dx, r.inv_dy, r.inv_dz, r.active);
}

// Loads rays [i, i + n) into a packet; lanes past n, and invalid rays, are inactive.
template <class A>
RayPacket<A> load_packet(const RayStream& s, std::size_t i, int n, simd::Floats<A>& tmax,
                         bool shear) {
  using F = simd::Floats<A>;
  constexpr int W = simd::kWidth<A>;
  // A whole packet straight from the columns; the stream's last, partial one by masked loads
  // (nothing past the columns' ends is read).
  auto col = [&](const Column<float>& c) {
    return n == W ? F::load_unaligned(c.data() + i) : simd::load_first<A>(c.data() + i, n);
  };
  RayPacket<A> r;
  r.ox = col(s.ox), r.oy = col(s.oy), r.oz = col(s.oz);
  r.dx = col(s.dx), r.dy = col(s.dy), r.dz = col(s.dz);
  r.tmin = col(s.tmin);
  tmax = col(s.tmax);
  r.time = s.time.empty() ? F(0.5f) : col(s.time);  // a scene without motion has no column
  // Whole packets load the aims straight too; a partial one's spare lanes are inactive.
  const auto none = simd::Ints<A>(int32_t(PrimRef::kInvalidBits));
  if (s.aim.empty()) {
    r.aim = none;
  } else if (n == W) {
    r.aim = simd::load<A>(reinterpret_cast<const int32_t*>(s.aim.data() + i));
  } else {
    alignas(64) int32_t end[W];
    for (int k = 0; k < W; ++k)
      end[k] = k < n ? int32_t(s.aim[i + std::size_t(k)]) : int32_t(PrimRef::kInvalidBits);
    r.aim = simd::load<A>(end);
  }
  set_reciprocal_and_validity<A>(r, tmax, simd::first_lanes<A>(n), shear);
  return r;
}

// Ray i of the stream as scalars, with its reciprocal direction.
inline RayScalars ray_scalars(const RayStream& s, std::size_t i) {
  RayScalars r{{s.ox[i], s.oy[i], s.oz[i]},
               {s.dx[i], s.dy[i], s.dz[i]},
               {},
               s.tmin[i],
               s.tmax[i],
               s.time_of(i)};
  for (int k = 0; k < 3; ++k)
    r.inv[k] = 1.0f / r.d[k];
  return r;
}

// One packet, closest hit or any hit, counted or not. Closest-hit packets of mixed directions
// walk the 8-wide tree where there is one (trace/wide_packet_traverse.h); the others the binary.
template <class A>
void traverse(const Scene& scene, const Bvh& bvh, RayPacket<A>& r, HitPacket<A>& h, bool any_hit,
              TraversalCounters* c) {
  const bool wide = !any_hit && !r.sides.uniform && !bvh.wide.empty();
  if (c) {
    ++c->packets;
    c->rays += uint64_t(__builtin_popcount(simd::bits<A>(r.active)));
    if (wide) return traverse_wide_packet<A, true>(scene, bvh, r, h, c);
    if (any_hit) return traverse_packet<A, true, true>(scene, bvh, r, h, c);
    return traverse_packet<A, false, true>(scene, bvh, r, h, c);
  }
  if (wide) return traverse_wide_packet<A, false>(scene, bvh, r, h, nullptr);
  if (any_hit) return traverse_packet<A, true>(scene, bvh, r, h);
  traverse_packet<A, false>(scene, bvh, r, h);
}

// Rays [begin, end) one at a time over the 8-wide tree, each in every lane of a packet
// (trace/single_ray.h: the packet's validity test and frame, worked out in scalar code).
template <class A>
void trace_range_single(const Scene& scene, const Bvh& bvh, const RayStream& rays,
                        std::size_t begin, std::size_t end, HitStream& hits, bool any_hit,
                        TraversalCounters* c) {
  using L = RayLanes<A>;
  using F = simd::Floats<L>;
  if (c) c->width = kWideArity;
  for (std::size_t i = begin; i < end; ++i) {
    RayScalars one = ray_scalars(rays, i);
    HitPacket<L> h;
    h.t = F(one.tmax);
    h.prim = simd::Ints<L>(int32_t(PrimRef::kInvalidBits));
    h.found = F(0.0f) != F(0.0f);
    bool valid = single_ray_valid(one) && !bvh.wide.empty();
    if (valid && c) ++c->packets, ++c->rays;
    // A ray aimed at a primitive goes through closest hit: blocked when that is something else.
    const uint32_t aim = rays.aim.empty() ? PrimRef::kInvalidBits : rays.aim[i];
    const bool plain_any_hit = any_hit && aim == PrimRef::kInvalidBits;
    if (valid) {
      RayPacket<L> r = broadcast_ray<L>(one);
      if (plain_any_hit) {
        c ? traverse_ray<A, true, true>(scene, bvh, r, h, c)
          : traverse_ray<A, true>(scene, bvh, r, h);
      } else {
        c ? traverse_ray<A, false, true>(scene, bvh, r, h, c)
          : traverse_ray<A, false>(scene, bvh, r, h);
      }
    }
    bool found = simd::any<L>(h.found);
    if (any_hit && !plain_any_hit) found = found && uint32_t(h.prim.get(0)) != aim;
    if (any_hit) {
      hits.t[i] = found ? 0.0f : std::numeric_limits<float>::infinity();
      hits.prim[i] = found ? 0u : PrimRef::kInvalidBits;
    } else {
      hits.t[i] = found ? h.t.get(0) : std::numeric_limits<float>::infinity();
      hits.prim[i] = found ? uint32_t(h.prim.get(0)) : PrimRef::kInvalidBits;
    }
  }
}

template <class A>
void trace_range(const Scene& scene, const Bvh& bvh, const RayStream& rays, std::size_t begin,
                 std::size_t end, HitStream& hits, bool any_hit, Traversal traversal,
                 TraversalCounters* counters) {
  if (traversal == Traversal::kSingleRays)
    return trace_range_single<A>(scene, bvh, rays, begin, end, hits, any_hit, counters);
  using F = simd::Floats<A>;
  constexpr int W = simd::kWidth<A>;
  const F inf(std::numeric_limits<float>::infinity());
  if (counters) counters->width = W;
  const bool shear = scene.table<Triangle>().size() != 0;  // only triangles read the frame
  for (std::size_t i = begin; i < end; i += W) {
    int n = int(std::min<std::size_t>(W, end - i));
    HitPacket<A> h;
    RayPacket<A> r = load_packet<A>(rays, i, n, h.t, shear);
    h.prim = simd::Ints<A>(int32_t(PrimRef::kInvalidBits));
    h.found = F(0.0f) != F(0.0f);
    if (simd::any<A>(r.active)) traverse<A>(scene, bvh, r, h, any_hit, counters);
    const F t = simd::select<A>(h.found, h.t, inf);
    // Occlusion: 0 where blocked. (A lane that met only its aim holds the aim's bits.)
    const simd::Ints<A> prim = any_hit
                                   ? simd::select<A>(h.found, simd::Ints<A>(0),
                                                     simd::Ints<A>(int32_t(PrimRef::kInvalidBits)))
                                   : h.prim;
    int32_t* prim_out = reinterpret_cast<int32_t*>(hits.prim.data() + i);
    if (n == W) {
      simd::store<A>(hits.t.data() + i, t);
      simd::store<A>(prim_out, prim);
      continue;
    }
    alignas(64) float t_buf[W];
    alignas(64) int32_t prim_buf[W];
    simd::store<A>(t_buf, t);
    simd::store<A>(prim_buf, prim);
    for (int k = 0; k < n; ++k)
      hits.t[i + k] = t_buf[k], prim_out[k] = prim_buf[k];
  }
}

// Where surfaces_range finds a request's hits and puts their surfaces. Request row r is:
// into the hit itself (hits[r], traced as the stream's ray r)... (The sinks are templates on
// the instruction set, though they do not use it, so that each per-ISA unit keeps its own copy
// of their inline functions: docs/design.md, "SIMD and the instruction sets".)
template <class A>
struct HitSink {
  static constexpr bool kTakesRuns = false;
  static constexpr bool kTakesFloats = false;
  Hit* hits;
  uint32_t ray_of(uint32_t r) const { return r; }
  uint32_t prim_row(uint32_t r) const { return hits[r].prim.row(); }
  double t_of(uint32_t r) const { return hits[r].t; }
  void store(uint32_t r, const glm::dvec3& p, const glm::dvec3& n, double cos_d,
             const glm::dvec3& /*error: a hit record's is Tracer::hit_point_bound*/) const {
    Hit& h = hits[r];
    h.surface = {p, n, n};
    h.front_face = cos_d < 0;
  }
};

// ... or into row r of columns, for hit ray[r] of a HitStream's columns (the render's lane rows).
template <class A>
struct ColumnSink {
  static constexpr bool kTakesRuns = true;
  static constexpr bool kTakesFloats = true;  // the float point's bound as well
  const uint32_t* ray;
  const float* t;        // HitStream::t
  const uint32_t* prim;  // HitStream::prim
  SurfaceColumns out;
  uint32_t ray_of(uint32_t r) const { return ray[r]; }
  uint32_t prim_row(uint32_t r) const { return PrimRef::from_bits(prim[ray[r]]).row(); }
  double t_of(uint32_t r) const { return t[ray[r]]; }
  // A double surface: rounded to float, its bound computed in double and rounded
  // (float_hit_point_bound's 2^-20 covers the rounding).
  void store(uint32_t r, const glm::dvec3& p, const glm::dvec3& n, double cos_d,
             const glm::dvec3& error) const {
    out.px[r] = float(p.x), out.py[r] = float(p.y), out.pz[r] = float(p.z);
    out.ngx[r] = float(n.x), out.ngy[r] = float(n.y), out.ngz[r] = float(n.z);
    out.nsx[r] = float(n.x), out.nsy[r] = float(n.y), out.nsz[r] = float(n.z);
    out.ex[r] = float(error.x), out.ey[r] = float(error.y), out.ez[r] = float(error.z);
    out.cos_ns[r] = cos_d;  // dot(d, n) = dot(n, d) bit for bit: the products commute
    out.front[r] = cos_d < 0;
  }
  // Rows [r, r + W) at once, from lanes: store's values, each column one store. The render's
  // rows are its rays in order, and neighbouring rays mostly meet the same kind, so a kind's
  // rows mostly come in runs.
  void store_run(uint32_t r, const SurfaceLanes<A>& s, const simd::Doubles<A>& cos_d,
                 const simd::DoubleVec3<A>& error) const {
    simd::store_narrowed<A>(out.px + r, s.p.x), simd::store_narrowed<A>(out.py + r, s.p.y);
    simd::store_narrowed<A>(out.pz + r, s.p.z);
    simd::store_narrowed<A>(out.ngx + r, s.n.x), simd::store_narrowed<A>(out.ngy + r, s.n.y);
    simd::store_narrowed<A>(out.ngz + r, s.n.z);
    simd::store_narrowed<A>(out.nsx + r, s.n.x), simd::store_narrowed<A>(out.nsy + r, s.n.y);
    simd::store_narrowed<A>(out.nsz + r, s.n.z);
    simd::store_narrowed<A>(out.ex + r, error.x), simd::store_narrowed<A>(out.ey + r, error.y);
    simd::store_narrowed<A>(out.ez + r, error.z);
    cos_d.store_unaligned(out.cos_ns + r);
    simd::store_flags<A>(out.front + r, simd::bits<A>(cos_d < simd::Doubles<A>(0.0)),
                         simd::kDoubleWidth<A>);
  }
};

// The surfaces of request rows `rows`, all on Kind, W hits per batch of double lanes; the
// last batch repeats its last hit in the spare lanes and stores only its own.
// The sink is copied first: ColumnSink stores the facing through a byte pointer, which may
// alias anything not provably local, so GCC reloaded each of its eleven column pointers for
// every row (perf: most of this loop's time on the course scene).
template <class A, class Kind, class Sink>
void surfaces_range(const typename Kind::Table& table, const RayStream& rays,
                    std::span<const uint32_t> rows, const Sink& to) {
  using D = simd::Doubles<A>;
  const Sink sink = to;
  constexpr int W = simd::kDoubleWidth<A>;
  for (std::size_t i = 0; i < rows.size(); i += W) {
    alignas(64) uint32_t at[W], prim_rows[W], ray_rows[W];
    alignas(64) double t[W];
    for (int k = 0; k < W; ++k) {
      const uint32_t r = rows[std::min(i + std::size_t(k), rows.size() - 1)];
      at[k] = r, prim_rows[k] = sink.prim_row(r), ray_rows[k] = sink.ray_of(r), t[k] = sink.t_of(r);
    }
    auto col = [&](const Column<float>& c) { return simd::load_rows<A>(c.data(), ray_rows); };
    const HitRayLanes<A> ray{{col(rays.ox), col(rays.oy), col(rays.oz)},
                             {col(rays.dx), col(rays.dy), col(rays.dz)},
                             D::load_aligned(t)};
    const SurfaceLanes<A> s = surface_lanes<A>(table, prim_rows, ray);
    const D cos_d = dot_lanes<A>(ray.d, s.n);
    // The float point's bound, for columns: in double, rounded as it is stored.
    simd::DoubleVec3<A> error{};
    if constexpr (Sink::kTakesFloats) error = float_hit_point_bound<D>(ray.o, ray.d, ray.t, s.p);
    if constexpr (Sink::kTakesRuns) {
      if (i + W <= rows.size() && simd::one_run<W>(at)) {
        sink.store_run(at[0], s, cos_d, error);
        continue;
      }
    }
    alignas(64) double out[10][W];
    const D* outs[10] = {&s.p.x, &s.p.y, &s.p.z,   &s.n.x,   &s.n.y,
                         &s.n.z, &cos_d, &error.x, &error.y, &error.z};
    for (int c = 0; c < 10; ++c)
      outs[c]->store_aligned(out[c]);
    const int n = int(std::min<std::size_t>(W, rows.size() - i));
    for (int k = 0; k < n; ++k)
      sink.store(at[k], {out[0][k], out[1][k], out[2][k]}, {out[3][k], out[4][k], out[5][k]},
                 out[6][k], {out[7][k], out[8][k], out[9][k]});
  }
}

template <class A, class Sink>
void surfaces_of_kind(const Scene& scene, const RayStream& rays, PrimTag kind,
                      std::span<const uint32_t> rows, const Sink& sink) {
  dispatch(kind, [&](auto k) {
    using Kind = decltype(k);
    if constexpr (Kind::surface_in_lanes)
      surfaces_range<A, Kind>(scene.table<Kind>(), rays, rows, sink);
  });
}

}  // namespace raylane::detail
