// 3×3 rotation matrices and quaternions, just enough for the orientation mini-language.
#pragma once

#include <cmath>

#include "raylane/core/vec3.h"

namespace raylane {

struct Mat3d {
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  static Mat3d identity() { return {}; }
  Vec3d row(int i) const { return {m[i][0], m[i][1], m[i][2]}; }
  Vec3d col(int j) const { return {m[0][j], m[1][j], m[2][j]}; }
  friend Vec3d operator*(const Mat3d& a, const Vec3d& v) {
    return {dot(a.row(0), v), dot(a.row(1), v), dot(a.row(2), v)};
  }
  friend Mat3d operator*(const Mat3d& a, const Mat3d& b) {
    Mat3d r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        r.m[i][j] = dot(a.row(i), b.col(j));
    return r;
  }
};

// Rotation by `degrees` about the unit axis `u`, right-hand rule (Rodrigues' formula).
Mat3d rotation_axis_angle(const Vec3d& u, double degrees);
// Rotation of the unit quaternion w + xi + yj + zk (Shoemake 1985, "Animating rotation
// with quaternion curves", the matrix of q·v·q*).
Mat3d rotation_quaternion(double w, double x, double y, double z);

}  // namespace raylane
