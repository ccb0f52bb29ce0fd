// Warps from the unit square to points and directions, with their densities (solid-angle
// measure), and an orthonormal frame: the geometry of sampling, shared by the primitive kinds
// (area sampling of emitters) and the path tracer. Every warp is total: u in [0, 1]² never
// gives NaN (docs/hard-cases.md N6).
#pragma once

#include "raylane/core/vec_math.h"

namespace raylane {

inline constexpr double kPi = 3.14159265358979323846;

// An orthonormal frame (s, t, n) around a unit vector n (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited", JCGT 6(1)): branch-free except for the sign of n.z.
struct Frame {
  glm::dvec3 s{}, t{}, n{};
  explicit Frame(const glm::dvec3& normal);
  glm::dvec3 to_world(const glm::dvec3& v) const { return s * v.x + t * v.y + n * v.z; }
  glm::dvec3 to_local(const glm::dvec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
};

// Cosine-weighted hemisphere around +z (Malley's method: a uniform disk point lifted up);
// pdf = cosθ/π.
glm::dvec3 sample_cosine_hemisphere(double u1, double u2);
inline double cosine_hemisphere_pdf(double cos_theta) {
  return cos_theta > 0 ? cos_theta / kPi : 0.0;
}

// A uniform point on the unit disc, by Shirley and Chiu's concentric map (1997, "A
// low-distortion map between disk and square"): squares of the [-1, 1]² grid go to rings, so
// the square's stratification survives (no polar map's pinch at the centre); pdf = 1/π.
// Returned as (x, y, 0).
glm::dvec3 sample_concentric_disc(double u1, double u2);

// A uniform direction on the unit sphere; pdf = 1/(4π).
glm::dvec3 sample_uniform_sphere(double u1, double u2);

}  // namespace raylane
