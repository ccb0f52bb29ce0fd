// Column<T>: a std::vector whose resize() leaves the new elements of a trivial T uninitialised,
// for the streams and queues that are refilled every depth of a render. There a resize makes
// room that is written next; value-initialising it first was a memset of a dozen columns per
// depth, 2.6 % of a course-scene render (perf, under write_lane_shadow_rays). Reading a row
// before writing it is a bug either way; with Column it is also an uninitialised read.
#pragma once

#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace raylane {

// std::allocator, except that construct() without arguments default-initialises: for a trivial
// type, nothing (resize(n) and vector(n) leave those elements as the memory held them).
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  constexpr DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  template <class U>
  void construct(U* at) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(at)) U;
  }
  template <class U, class... Args>
  void construct(U* at, Args&&... args) {
    ::new (static_cast<void*>(at)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using Column = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace raylane
