// Shared by the kernels of closed solids (sphere, box, cylinder).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "raylane/core/ray.h"

namespace raylane {

// A closed solid meets the ray's line in [tn, tf]; the surface hit is the first of the two
// inside (tmin, tmax), so a ray starting inside hits the exit point. +inf when neither is.
inline double first_in_range(double tn, double tf, const Rayd& ray) {
  if (tn > ray.tmin && tn < ray.tmax) return tn;
  if (tf > ray.tmin && tf < ray.tmax) return tf;
  return std::numeric_limits<double>::infinity();
}

// The roots of a·t² + 2b·t + c = 0 given disc = b² − a·c ≥ 0 as Δ = a·(r² − |l|²) (Hearn and
// Baker's form, which does not cancel for far, small shapes), by the Press form
// q = −(b + sign(b)·√Δ), t = c/q and q/a (Numerical Recipes §5.6; Haines et al., Ray Tracing
// Gems ch. 7). Branches on b < 0 rather than a sign() that could return 0 (docs/hard-cases.md S5).
// Returns the ordered roots.
inline void solve_quadratic(double a, double b, double c, double delta, double& t0, double& t1) {
  double sq = std::sqrt(delta);
  double q = b < 0 ? -b + sq : -b - sq;
  if (q == 0) {  // b = 0 and a tangent: a double root at 0
    t0 = t1 = 0;
    return;
  }
  double r0 = c / q, r1 = q / a;
  t0 = std::min(r0, r1);
  t1 = std::max(r0, r1);
}

}  // namespace raylane
