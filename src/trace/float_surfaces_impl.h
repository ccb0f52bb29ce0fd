// The float surfaces' pass of the SIMD tracer (SimdTracer::float_surfaces): the render's lane
// rows' surfaces in float lanes, every kind that has them in one pass in row order. Part of the
// body of the SIMD tracer, instantiated once per instruction set through
// src/trace/simd_tracer_impl.h. Include from nowhere else.
#pragma once

#include <algorithm>
#include <bit>
#include <numeric>
#include <span>

#include "raylane/prims/prim_packets.h"
#include "raylane/scene/scene.h"
#include "raylane/simd/lane_rows.h"
#include "raylane/simd/surface_lanes.h"
#include "raylane/trace/ray_stream.h"
#include "raylane/trace/surface_columns.h"

namespace raylane::detail {

// The lanes `on` of `from` into `into`.
template <class A>
void blend3(const simd::Mask<A>& on, const simd::FloatVec3<A>& from, simd::FloatVec3<A>& into) {
  into = {simd::select<A>(on, from.x, into.x), simd::select<A>(on, from.y, into.y),
          simd::select<A>(on, from.z, into.z)};
}

// Whether a kind's shading normal differs from its geometric one (triangles: interpolated from
// the vertices'); false unless the kind says so.
template <class Kind>
constexpr bool has_shading_normal() {
  if constexpr (requires { Kind::has_shading_normal; })
    return Kind::has_shading_normal;
  else
    return false;
}

// Whether a kind's float surfaces are computed out of the surfaces' pass's loop, in
// rare_float_surfaces: a kind that few of a render's batches hold (cylinders, moving spheres),
// whose code inlined into the loop cost its common batches registers (bench/README.md, "Cylinders'
// and moving spheres' surfaces in float lanes"); false unless the kind says so.
template <class Kind>
constexpr bool float_surface_out_of_line() {
  return requires {
    requires Kind::float_surface_out_of_line;
  };
}

// The kinds out of the loop (float_surface_out_of_line), for a batch that holds one: their
// surfaces and their lanes, returned by value. One call for all of them, and nothing of the
// loop's passed by reference: a batch's surfaces whose address a call takes live in memory for
// every batch.
template <class A>
struct RareSurfaces {
  FloatSurfaceLanes<A> s;
  simd::Mask<A> on;
};
template <class A>
[[gnu::noinline]] RareSurfaces<A> rare_float_surfaces(const Scene& scene, const simd::Ints<A>& tag,
                                                      const simd::Ints<A>& row, uint32_t lanes,
                                                      const FloatHitRayLanes<A>& r) {
  using I = simd::Ints<A>;
  RareSurfaces<A> out;  // set by the first kind present: the caller has one
  out.on = simd::Mask<A>(false);
  bool first = true;
  PrimKinds::for_each([&](auto kind) {
    using Kind = decltype(kind);
    if constexpr (Kind::surface_in_float_lanes && float_surface_out_of_line<Kind>()) {
      static_assert(!has_shading_normal<Kind>(), "a kind out of the loop has one normal");
      const simd::Mask<A> on = simd::equal<A>(tag, I(int32_t(tag_of<Kind>)));
      if ((simd::bits<A>(on) & lanes) == 0) return;
      const FloatSurfaceLanes<A> k =
          surface_float_lanes<A>(scene.table<Kind>(), simd::select<A>(on, row, I(0)), r);
      if (first) {
        out.s = k, first = false;
      } else {
        blend3<A>(on, k.p, out.s.p), blend3<A>(on, k.ng, out.s.ng);
        blend3<A>(on, k.error, out.s.error);
      }
      out.on = out.on | on;
    }
  });
  return out;
}

// The float surfaces of request rows [0, ray.size()) in the rows' order, W rows per batch of
// float lanes: every kind with surface_in_float_lanes in the one pass, each kind present in a
// batch computed for the whole batch and blended in by its lanes. The rows are the render's
// rays in order, so the batch's rays mostly load whole or from a short window (RowReader), and
// its columns always store whole: grouping the rows by kind first cost a gather of every ray
// column and a scalar store of every surface column wherever kinds interleave (perf: most of
// the box surfaces' time on the course scene). The rows of the other kinds are listed in `rest`, in
// order, for surfaces_of_kind; their rows here hold nothing of use until it writes them. Returns
// their count.
template <class A>
std::size_t float_surfaces_in_row_order(const Scene& scene, const RayStream& rays,
                                        std::span<const uint32_t> ray, const HitStream& hits,
                                        const SurfaceColumns& out, uint32_t* rest) {
  using F = simd::Floats<A>;
  using I = simd::Ints<A>;
  constexpr int W = simd::kWidth<A>;
  const SurfaceColumns to = out;  // local: the facing's byte stores alias nothing provably
  const std::size_t n = ray.size();
  bool any_ours = false;  // a scene of CSG, SDFs or cylinders alone: every row in `rest`
  PrimKinds::for_each([&](auto kind) {
    if constexpr (decltype(kind)::surface_in_float_lanes)
      any_ours = any_ours || scene.table<decltype(kind)>().size() != 0;
  });
  if (!any_ours) {
    std::iota(rest, rest + n, 0u);
    return n;
  }
  std::size_t rest_count = 0;
  for (std::size_t i = 0; i < n; i += W) {
    const int m = int(std::min<std::size_t>(W, n - i));
    // A whole batch reads its rows in place: copied to the stack first, they were stored in
    // 16-byte halves and loaded as one register, which stalls (a load spanning two pending
    // stores cannot take its value from them).
    alignas(64) uint32_t last_rows[W];
    const uint32_t* ray_rows = ray.data() + i;
    if (m < W) {
      for (int k = 0; k < W; ++k)
        last_rows[k] = ray[i + std::size_t(std::min(k, m - 1))];
      ray_rows = last_rows;
    }
    const simd::RowReader<A> read(ray_rows);  // the rays mostly a run, else close together
    auto col = [&](const float* c) { return read.read(c); };
    const I prim = xsimd::bitwise_cast<I>(col(reinterpret_cast<const float*>(hits.prim.data())));
    const I tag = (prim >> PrimRef::kRowBits) & I((1 << PrimRef::kTagBits) - 1);
    const I row = prim & I(int32_t(PrimRef::kMaxRows - 1));
    const uint32_t lanes = (1u << m) - 1;  // the batch's own rows
    auto lanes_of = [&](PrimTag kind) { return simd::equal<A>(tag, I(int32_t(kind))); };
    uint32_t ours = 0, rare = 0;  // the lanes whose kind has float surfaces; out of the loop
    PrimKinds::for_each([&](auto kind) {
      using Kind = decltype(kind);
      if constexpr (Kind::surface_in_float_lanes) {
        const uint32_t bits = simd::bits<A>(lanes_of(tag_of<Kind>)) & lanes;
        ours |= bits;
        if constexpr (float_surface_out_of_line<Kind>()) rare |= bits;
      }
    });
    for (uint32_t others = lanes & ~ours; others != 0; others &= others - 1)
      rest[rest_count++] = uint32_t(i) + uint32_t(std::countr_zero(others));
    if (ours == 0) continue;  // a batch of the other kinds: nothing to read or store here
    const FloatHitRayLanes<A> r{{col(rays.ox.data()), col(rays.oy.data()), col(rays.oz.data())},
                                {col(rays.dx.data()), col(rays.dy.data()), col(rays.dz.data())},
                                col(hits.t.data()),
                                rays.time.empty() ? nullptr : rays.time.data(),
                                ray_rows};
    // Set by the first kind present. The shading normal is the geometric one but in the lanes
    // of a kind with its own (`smooth`): blending it for every kind cost the spheres' and
    // boxes' batches a third set of selects.
    FloatSurfaceLanes<A> s{};
    simd::FloatVec3<A> own_ns{};
    simd::Mask<A> smooth(false);
    uint32_t done = 0;
    PrimKinds::for_each([&](auto kind) {
      using Kind = decltype(kind);
      if constexpr (Kind::surface_in_float_lanes && !float_surface_out_of_line<Kind>()) {
        const simd::Mask<A> on = lanes_of(tag_of<Kind>);
        const uint32_t bits = simd::bits<A>(on) & lanes;
        if (bits == 0) return;
        // Lanes of other kinds read the table's row 0, which exists: this kind has a hit.
        const FloatSurfaceLanes<A> k =
            surface_float_lanes<A>(scene.table<Kind>(), simd::select<A>(on, row, I(0)), r);
        if (done == 0) {
          s.p = k.p, s.ng = k.ng, s.error = k.error;
        } else {
          blend3<A>(on, k.p, s.p), blend3<A>(on, k.ng, s.ng), blend3<A>(on, k.error, s.error);
        }
        if constexpr (has_shading_normal<Kind>()) own_ns = k.ns, smooth = on;
        done |= bits;
      }
    });
    if (rare != 0) {
      const RareSurfaces<A> k = rare_float_surfaces<A>(scene, tag, row, lanes, r);
      if (done == 0) {
        s.p = k.s.p, s.ng = k.s.ng, s.error = k.s.error;
      } else {
        blend3<A>(k.on, k.s.p, s.p), blend3<A>(k.on, k.s.ng, s.ng);
        blend3<A>(k.on, k.s.error, s.error);
      }
    }
    s.ns = s.ng;
    if (simd::any<A>(smooth)) blend3<A>(smooth, own_ns, s.ns);
    const F cos_ns = r.d.x * s.ns.x + r.d.y * s.ns.y + r.d.z * s.ns.z;
    const uint32_t front =
        simd::bits<A>(r.d.x * s.ng.x + r.d.y * s.ng.y + r.d.z * s.ng.z < F(0.0f));
    if (m == W) {
      auto store3 = [&](float* x, float* y, float* z, const simd::FloatVec3<A>& v) {
        simd::store<A>(x + i, v.x), simd::store<A>(y + i, v.y), simd::store<A>(z + i, v.z);
      };
      store3(to.px, to.py, to.pz, s.p), store3(to.ngx, to.ngy, to.ngz, s.ng);
      store3(to.nsx, to.nsy, to.nsz, s.ns), store3(to.ex, to.ey, to.ez, s.error);
      simd::store_widened<A>(to.cos_ns + i, cos_ns);
    } else {
      // The batch's m rows, through a buffer. The lanes are stored by value: a table of their
      // addresses kept the whole batch's surface in memory, and every kind's blend spilled.
      alignas(64) float buffer[W];
      auto part = [&](const F& v, float* into) {
        v.store_aligned(buffer);
        std::copy_n(buffer, m, into + i);
      };
      auto part3 = [&](const simd::FloatVec3<A>& v, float* x, float* y, float* z) {
        part(v.x, x), part(v.y, y), part(v.z, z);
      };
      part3(s.p, to.px, to.py, to.pz), part3(s.ng, to.ngx, to.ngy, to.ngz);
      part3(s.ns, to.nsx, to.nsy, to.nsz), part3(s.error, to.ex, to.ey, to.ez);
      cos_ns.store_aligned(buffer);
      for (int k = 0; k < m; ++k)
        to.cos_ns[i + std::size_t(k)] = buffer[k];
    }
    simd::store_flags<A>(to.front + i, front, m);
  }
  return rest_count;
}

}  // namespace raylane::detail
