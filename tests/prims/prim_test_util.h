// Helpers for the primitive tests: one-row tables and rays.
#pragma once

#include <array>
#include <cmath>
#include <limits>

#include "raylane/prims/prim_list.h"

namespace raylane::testing {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline SphereTable one_sphere(double x, double y, double z, double r) {
  SphereTable t;
  t.append(std::array<double, 4>{x, y, z, r}, 0);
  return t;
}
inline BoxTable one_box(glm::dvec3 b, glm::dvec3 d) {
  BoxTable t;
  t.append(std::array<double, 6>{b.x, b.y, b.z, d.x, d.y, d.z}, 0);
  return t;
}
inline CylinderTable one_cylinder(glm::dvec3 b, glm::dvec3 a, double r) {
  CylinderTable t;
  t.append(std::array<double, 7>{b.x, b.y, b.z, a.x, a.y, a.z, r}, 0);
  return t;
}
inline void add_triangle(TriangleTable& t, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  glm::vec3 n(normalize(cross(b - a, c - a)));
  if (!is_finite(n)) n = glm::vec3(0, 0, 1);
  t.append({glm::vec3(a), glm::vec3(b), glm::vec3(c)}, {n, n, n}, 0);
}
inline Rayd ray(glm::dvec3 o, glm::dvec3 d) {
  return {o, d};
}

}  // namespace raylane::testing
