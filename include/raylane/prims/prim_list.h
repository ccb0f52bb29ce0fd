// The list of primitive kinds and the one switch over them. Adding a kind means its header
// family in prims/ (<kind>.h: table, traits, reference; <kind>_packet.h: the SIMD kernel), one
// entry in PrimKinds and one include in prim_packets.h (docs/design.md, "Tagged dispatch").
//
// What every kind's traits struct provides (Sphere in sphere.h is the example):
//   using Table;                      its SoA table (append, bounds, size, columns)
//   name, plural                      for messages
//   keyword, param_count              its scene command and parameter count ("" and 0: none)
//   two_sided                         a surface seen, lit and emitting from both sides (else a
//                                     closed solid: outside only)
//   sah_test_cost                     one primitive test, relative to a BVH node visit
//   area(t, i), sample_area(t, i, u_part, u1, u2)   uniform area sampling, for emitters
//   surface_in_lanes, surface_in_float_lanes   whether <kind>_packet.h computes its hits'
//                                     surfaces in double lanes (surface_lanes, the reference's
//                                     bits) and in float lanes with error bounds
//                                     (surface_float_lanes, the render's columns)
//   float_surface_out_of_line (optional)  true for a kind that few of a render's batches hold:
//                                     its float surfaces are computed out of the surfaces'
//                                     pass's loop (src/trace/float_surfaces_impl.h)
// and may provide (found with `requires` where used):
//   sample_subtended, subtended_solid_angle   emitter sampling by the solid angle the
//                                     primitive subtends, better than by area (spheres)
//   area_seen_from, sample_area_seen_from   emitter sampling by area over the part of the
//                                     surface that faces the point, not all of it (boxes,
//                                     cylinders)
//   point_light(t, i)                 the point the course's `lit` view lights from (spheres)
//   has_shading_normal                a shading normal of its own in the float surfaces
//                                     (triangles: interpolated from the vertex normals)
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

#include "raylane/core/prim_ref.h"
#include "raylane/prims/box.h"
#include "raylane/prims/csg.h"
#include "raylane/prims/cylinder.h"
#include "raylane/prims/moving_sphere.h"
#include "raylane/prims/sdf.h"
#include "raylane/prims/sphere.h"
#include "raylane/prims/triangle.h"

namespace raylane {

template <class... Kinds>
struct KindList {
  static constexpr std::size_t size = sizeof...(Kinds);
  using Tables = std::tuple<typename Kinds::Table...>;

  // Calls f(Kind{}) for every kind, in list order.
  template <class F>
  static constexpr void for_each(F&& f) {
    (f(Kinds{}), ...);
  }

  // The position of Kind in the list.
  template <class Kind>
  static constexpr std::size_t index_of() {
    constexpr bool is[] = {std::is_same_v<Kind, Kinds>...};
    for (std::size_t i = 0; i < size; ++i)
      if (is[i]) return i;
    return size;
  }
};

// New kinds go last: a kind's tag is its position, and the tags of the others stay as they were.
using PrimKinds = KindList<Sphere, Box, Cylinder, Triangle, MovingSphere, Csg, Sdf>;
using PrimTables = PrimKinds::Tables;
inline constexpr std::size_t kPrimKindCount = PrimKinds::size;
static_assert(kPrimKindCount <= (std::size_t(1) << PrimRef::kTagBits),
              "PrimRef has room for 2^kTagBits kinds");

// Kind's tag: its position in PrimKinds.
template <class Kind>
inline constexpr PrimTag tag_of = [] {
  static_assert(PrimKinds::index_of<Kind>() < kPrimKindCount, "not in PrimKinds");
  return PrimTag(PrimKinds::index_of<Kind>());
}();

template <class Kind>
constexpr std::size_t kind_index() {
  return std::size_t(tag_of<Kind>);
}

namespace detail {
template <class F, class First, class... Kinds>
constexpr decltype(auto) dispatch_impl(PrimTag tag, F&& f, KindList<First, Kinds...>) {
  using R = std::invoke_result_t<F, First>;
  if constexpr (std::is_void_v<R>) {
    // (void): the fold is evaluated for its short-circuit, not its value (clang warns).
    (void)((tag == tag_of<First> ? (f(First{}), true) : false) ||
           ((tag == tag_of<Kinds> ? (f(Kinds{}), true) : false) || ...));
  } else {
    R result{};
    (void)((tag == tag_of<First> ? (result = f(First{}), true) : false) ||
           ((tag == tag_of<Kinds> ? (result = f(Kinds{}), true) : false) || ...));
    return result;
  }
}
}  // namespace detail

// Calls f(Kind{}) for the kind whose tag is `tag`; the only switch over kinds.
template <class F>
constexpr decltype(auto) dispatch(PrimTag tag, F&& f) {
  return detail::dispatch_impl(tag, std::forward<F>(f), PrimKinds{});
}

// Facts of a kind known only by its tag.
inline std::string_view kind_name(PrimTag tag) {
  return dispatch(tag, [](auto kind) { return decltype(kind)::name; });
}
inline bool kind_two_sided(PrimTag tag) {
  return dispatch(tag, [](auto kind) { return decltype(kind)::two_sided; });
}
inline double kind_sah_test_cost(PrimTag tag) {
  return dispatch(tag, [](auto kind) { return decltype(kind)::sah_test_cost; });
}

// A reference hit on row `row` of Kind: its t and the row the hit names, which is the row itself
// unless the kind's hits name a part of it (a CSG block's leaf: Kind::hit_ref).
struct RowHit {
  double t;
  uint32_t row;
};
template <class Kind>
RowHit hit_ref(const typename Kind::Table& table, uint32_t row, const Rayd& ray) {
  if constexpr (requires { Kind::hit_ref(table, row, ray); }) {
    auto h = Kind::hit_ref(table, row, ray);
    return {h.t, h.row};
  } else {
    return {intersect_ref(table, row, ray), row};
  }
}

// Whether Kind's hits name the row the tree holds, as a sphere's do; a CSG or SDF block's hits
// name one of its leaves (Kind::hit_ref).
template <class Kind>
constexpr bool hits_name_their_row() {
  return !requires(const typename Kind::Table& table, uint32_t row, const Rayd& ray) {
    Kind::hit_ref(table, row, ray);
  };
}

inline bool kind_hits_name_their_row(PrimTag tag) {
  return dispatch(tag, [](auto kind) { return hits_name_their_row<decltype(kind)>(); });
}

// "sphere#12", or "none".
inline std::string to_string(PrimRef ref) {
  if (!ref.valid()) return "none";
  std::string kind = std::size_t(ref.tag()) < kPrimKindCount
                         ? std::string(kind_name(ref.tag()))
                         : "kind" + std::to_string(int(ref.tag()));
  return kind + "#" + std::to_string(ref.row());
}

}  // namespace raylane
