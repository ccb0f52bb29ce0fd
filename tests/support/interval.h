// Interval arithmetic in double around float computations: each interval holds every value
// a float kernel can produce for some quantity (pbrt-v4's `Interval`, src/pbrt/util/float.h,
// which runs inside pbrt's kernels; ours runs beside raylane's). Used by error_bands.cpp
// and error_bands_scene.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "raylane/core/float_util.h"

namespace raylane::testing {

// Distance between two values that may both be the same infinity.
inline double gap(double a, double b) {
  return a == b ? 0.0 : std::abs(a - b);
}

// A closed interval; the default holds everything.
struct Interval {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  static Interval point(double x) { return {x, x}; }
  static Interval around(double x, double err) { return {x - err, x + err}; }
  static Interval everything() { return {}; }
  bool contains_zero() const { return lo <= 0 && hi >= 0; }
};

namespace interval_detail {
// Endpoints are computed in double: 2^-50 relative more covers that rounding.
constexpr double kEndpointSlack = 0x1p-50;
inline double grow_up(double x, double rel) {
  return std::isfinite(x) ? x + rel * std::abs(x) : x;
}
inline double grow_down(double x, double rel) {
  return std::isfinite(x) ? x - rel * std::abs(x) : x;
}
// inf − inf and 0·inf: the operation could give anything.
inline Interval sanitize(Interval x) {
  if (std::isnan(x.lo)) x.lo = -std::numeric_limits<double>::infinity();
  if (std::isnan(x.hi)) x.hi = std::numeric_limits<double>::infinity();
  return x;
}
template <int N>
Interval hull_of(const double (&p)[N]) {
  for (double v : p)
    if (std::isnan(v)) return Interval::everything();
  return {*std::min_element(p, p + N), *std::max_element(p, p + N)};
}
}  // namespace interval_detail

// A relative error of at most `rel` on every value of x.
inline Interval widen(Interval x, double rel) {
  using namespace interval_detail;
  return {grow_down(x.lo, rel + kEndpointSlack), grow_up(x.hi, rel + kEndpointSlack)};
}
// One float rounding (relative error ≤ u = 2^-24).
inline Interval rounded(Interval x) {
  return widen(x, kFloatUnitRoundoff);
}
inline Interval operator-(Interval a) {
  return {-a.hi, -a.lo};
}
inline Interval operator+(Interval a, Interval b) {
  return interval_detail::sanitize({a.lo + b.lo, a.hi + b.hi});
}
inline Interval operator-(Interval a, Interval b) {
  return interval_detail::sanitize({a.lo - b.hi, a.hi - b.lo});
}
inline Interval operator*(Interval a, Interval b) {
  double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return interval_detail::hull_of(p);
}
inline Interval operator/(Interval a, Interval b) {
  if (b.contains_zero()) return Interval::everything();
  double p[4] = {a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi};
  return interval_detail::hull_of(p);
}
inline Interval imin(Interval a, Interval b) {
  return {std::min(a.lo, b.lo), std::min(a.hi, b.hi)};
}
inline Interval imax(Interval a, Interval b) {
  return {std::max(a.lo, b.lo), std::max(a.hi, b.hi)};
}
inline Interval hull(Interval a, Interval b) {
  return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}
inline Interval clamp_nonneg(Interval a) {
  return {std::max(a.lo, 0.0), std::max(a.hi, 0.0)};
}
inline Interval isqrt(Interval a) {
  return {std::sqrt(std::max(a.lo, 0.0)), std::sqrt(std::max(a.hi, 0.0))};
}
inline Interval square_nonneg(Interval a) {
  double lo = std::max(a.lo, 0.0);
  return {lo * lo, a.hi * a.hi};
}

}  // namespace raylane::testing
