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
inline BoxTable one_box(Vec3d b, Vec3d d) {
  BoxTable t;
  t.append(std::array<double, 6>{b.x, b.y, b.z, d.x, d.y, d.z}, 0);
  return t;
}
inline CylinderTable one_cylinder(Vec3d b, Vec3d a, double r) {
  CylinderTable t;
  t.append(std::array<double, 7>{b.x, b.y, b.z, a.x, a.y, a.z, r}, 0);
  return t;
}
inline void add_triangle(TriangleTable& t, Vec3d a, Vec3d b, Vec3d c) {
  Vec3f n(normalize(cross(b - a, c - a)));
  if (!is_finite(n)) n = Vec3f(0, 0, 1);
  t.append({Vec3f(a), Vec3f(b), Vec3f(c)}, {n, n, n}, 0);
}
inline Rayd ray(Vec3d o, Vec3d d) {
  return {o, d};
}

}  // namespace raylane::testing
