// Signed-distance blocks' program (docs/scene-language.md, "SDF blocks"): the
// codes, the exact distances of the leaves and the operators that combine them, written once
// over the number type (double for the reference marcher, float for lanes).
//
// Leaf distances are Quilez's exact ones ("distance functions", iquilezles.org): negative
// inside, |gradient| = 1 almost everywhere, so a step of the distance never crosses the surface
// (Hart 1996, "Sphere tracing", Graphics Visual Computer 12(10), §2: a step of a distance
// bound is safe). min and max of bounds are bounds again, so the sharp operators keep that
// property; the smooth ones use Quilez's polynomial smooth minimum ("smooth minimum",
// iquilezles.org): h = max(k − |a − b|, 0)/k, smin = min(a, b) − h²k/4, which moves the
// surface by at most k/4.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string_view>

#include "raylane/core/vec_math.h"
#include "raylane/prims/csg_program.h"

namespace raylane {

// A program code: a leaf's index within its block, a sharp operator (the CSG codes), or a
// smooth one, whose width k is the program's k column at the same position.
enum SdfCode : uint32_t {
  kSdfUnion = kCsgUnion,
  kSdfIntersect = kCsgIntersect,
  kSdfDifference = kCsgDifference,
  kSdfSmoothUnion = 0x103,
  kSdfSmoothIntersect = 0x104,
  kSdfSmoothDifference = 0x105,
};

// Leaves per block: the evaluation stack lives on the stack (nothing allocated per ray).
inline constexpr uint32_t kSdfMaxLeaves = 64;

inline bool sdf_is_smooth(uint32_t code) {
  return code >= kSdfSmoothUnion && code <= kSdfSmoothDifference;
}

inline std::string_view sdf_code_name(uint32_t code) {
  switch (code) {
    case kSdfSmoothUnion:
      return "smoothunion";
    case kSdfSmoothIntersect:
      return "smoothintersect";
    case kSdfSmoothDifference:
      return "smoothdifference";
    default:
      return csg_code_name(code);
  }
}

// Quilez's polynomial smooth minimum of width k > 0.
template <class T>
T sdf_smin(T a, T b, T k) {
  T h = std::max(k - std::abs(a - b), T(0)) / k;
  return std::min(a, b) - h * h * k * T(0.25);
}

// A op B for distances a (of A) and b (of B): union min, intersection max, difference
// max(a, −b); the smooth forms through smin, with max(a, b) = −smin(−a, −b).
template <class T>
T sdf_combine(uint32_t code, T a, T b, T k) {
  switch (code) {
    case kSdfUnion:
      return std::min(a, b);
    case kSdfIntersect:
      return std::max(a, b);
    case kSdfDifference:
      return std::max(a, -b);
    case kSdfSmoothUnion:
      return sdf_smin(a, b, k);
    case kSdfSmoothIntersect:
      return -sdf_smin(-a, -b, k);
    default:
      return -sdf_smin(-a, b, k);
  }
}

// Distances of the leaves at p (Quilez, "distance functions"). Axes are unit vectors.
template <class T>
T sdf_sphere(const glm::vec<3, T>& p, const glm::vec<3, T>& c, T r) {
  return length(p - c) - r;
}

// An axis-aligned box of centre c and half extents e.
template <class T>
T sdf_box(const glm::vec<3, T>& p, const glm::vec<3, T>& c, const glm::vec<3, T>& e) {
  glm::vec<3, T> q = abs(p - c) - e;
  T inside = std::min(std::max(q.x, std::max(q.y, q.z)), T(0));
  return length(max(q, glm::vec<3, T>(0))) + inside;
}

// The distance from the axis through c along u (unit) and the height along it: the radial
// part is |f × u|, which does not cancel as sqrt(|f|² − y²) does near the axis.
template <class T>
void sdf_axial(const glm::vec<3, T>& p, const glm::vec<3, T>& c, const glm::vec<3, T>& u, T& radial,
               T& height) {
  glm::vec<3, T> f = p - c;
  height = dot(f, u);
  radial = length(cross(f, u));
}

// A capped cylinder of middle c, unit axis u, half height hh, radius r.
template <class T>
T sdf_cylinder(const glm::vec<3, T>& p, const glm::vec<3, T>& c, const glm::vec<3, T>& u, T hh,
               T r) {
  T x, y;
  sdf_axial(p, c, u, x, y);
  T dx = x - r, dy = std::abs(y) - hh;
  T outside =
      std::sqrt(std::max(dx, T(0)) * std::max(dx, T(0)) + std::max(dy, T(0)) * std::max(dy, T(0)));
  return std::min(std::max(dx, dy), T(0)) + outside;
}

// A torus of centre c, unit axis u, major radius R and tube radius r.
template <class T>
T sdf_torus(const glm::vec<3, T>& p, const glm::vec<3, T>& c, const glm::vec<3, T>& u, T R, T r) {
  T x, y;
  sdf_axial(p, c, u, x, y);
  return std::sqrt((x - R) * (x - R) + y * y) - r;
}

}  // namespace raylane
