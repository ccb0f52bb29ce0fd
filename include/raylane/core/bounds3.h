// Axis-aligned bounding box. An empty box has lo = +inf, hi = -inf, so extending it by
// any point gives that point.
#pragma once

#include <limits>

#include "raylane/core/float_util.h"
#include "raylane/core/vec_math.h"

namespace raylane {

template <class T>
struct Bounds3 {
  static constexpr T inf = std::numeric_limits<T>::infinity();
  glm::vec<3, T> lo{inf, inf, inf};
  glm::vec<3, T> hi{-inf, -inf, -inf};

  constexpr Bounds3() = default;
  constexpr Bounds3(const glm::vec<3, T>& a, const glm::vec<3, T>& b)
      : lo(min(a, b)), hi(max(a, b)) {}

  constexpr bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  constexpr void extend(const glm::vec<3, T>& p) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  constexpr void extend(const Bounds3& b) {
    lo = min(lo, b.lo);
    hi = max(hi, b.hi);
  }
  constexpr glm::vec<3, T> diagonal() const { return hi - lo; }
  constexpr glm::vec<3, T> centroid() const { return (lo + hi) * T(0.5); }
  // Half the surface area: the SAH only ever uses ratios of areas.
  constexpr T half_area() const {
    if (empty()) return T(0);
    glm::vec<3, T> d = diagonal();
    return d.x * d.y + d.y * d.z + d.z * d.x;
  }
  constexpr bool contains(const glm::vec<3, T>& p) const {
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
  }
  constexpr bool contains(const Bounds3& b) const {
    return b.empty() || (contains(b.lo) && contains(b.hi));
  }
};

using Bounds3f = Bounds3<float>;
using Bounds3d = Bounds3<double>;

// The float box that surely contains a double box: each bound is rounded to float and then
// stepped one float outward, so rounding to nearest can never cut off a tangent hit
// (docs/hard-cases.md C7).
inline Bounds3f round_out(const Bounds3d& b) {
  Bounds3f r;
  for (int i = 0; i < 3; ++i) {
    r.lo[i] = next_float_down(float(b.lo[i]));
    r.hi[i] = next_float_up(float(b.hi[i]));
  }
  return r;
}

}  // namespace raylane
