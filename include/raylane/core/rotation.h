// Rotations for the orientation mini-language: glm::dmat3 (column-major: r[j] is column j,
// r[j][i] the element of row i) and glm::dquat (w + xi + yj + zk, built as glm::dquat(w, x, y, z)
// and turned into a matrix by glm::mat3_cast, the matrix of q·v·q* of Shoemake 1985, "Animating
// rotation with quaternion curves").
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "raylane/core/vec_math.h"

namespace raylane {

// Rotation by `degrees` about the unit axis `u`, right-hand rule (Rodrigues' formula). Not
// glm::angleAxis: the orientation tests hold this formula's products to 1e-15.
glm::dmat3 rotation_axis_angle(const glm::dvec3& u, double degrees);

}  // namespace raylane
