// The list of primitive kinds and the one switch over them. Adding a kind means one header in
// prims/ and one entry in PrimKinds (design.md, "Tagged dispatch").
#pragma once

#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

#include "raylane/prims/box.h"
#include "raylane/prims/cylinder.h"
#include "raylane/prims/prim_ref.h"
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
};

using PrimKinds = KindList<Sphere, Box, Cylinder, Triangle>;
using PrimTables = PrimKinds::Tables;

namespace detail {
template <class F, class... Kinds>
constexpr decltype(auto) dispatch_impl(PrimTag tag, F&& f, KindList<Kinds...>) {
  using R = std::invoke_result_t<F, Sphere>;
  if constexpr (std::is_void_v<R>) {
    // (void): the fold is evaluated for its short-circuit, not its value (clang warns).
    (void)((tag == Kinds::tag ? (f(Kinds{}), true) : false) || ...);
  } else {
    R result{};
    (void)((tag == Kinds::tag ? (result = f(Kinds{}), true) : false) || ...);
    return result;
  }
}
}  // namespace detail

// Calls f(Kind{}) for the kind whose tag is `tag`; the only switch over kinds.
template <class F>
constexpr decltype(auto) dispatch(PrimTag tag, F&& f) {
  return detail::dispatch_impl(tag, std::forward<F>(f), PrimKinds{});
}

template <class Kind>
constexpr std::size_t kind_index() {
  return std::size_t(Kind::tag);
}

static_assert(PrimKinds::size == kPrimKindCount);
static_assert(kind_index<Sphere>() == 0 && kind_index<Box>() == 1 && kind_index<Cylinder>() == 2 &&
                  kind_index<Triangle>() == 3,
              "PrimTag values must follow the order of PrimKinds");

}  // namespace raylane
