// Spheres as emitters: area, area sampling and sampling of the subtended cone.
#include <algorithm>
#include <cmath>

#include "raylane/core/warps.h"
#include "raylane/prims/sphere.h"

namespace raylane {

namespace {
// 1 − cos θmax of the cone a sphere of radius² r2 subtends from distance² d2 > r2, without
// cancellation: sin²θmax / (1 + cos θmax).
double cone_one_minus_cos(double r2, double d2) {
  double sin2 = r2 / d2;
  return sin2 / (1 + std::sqrt(std::max(0.0, 1 - sin2)));
}
}  // namespace

double Sphere::area(const Table& t, uint32_t i) {
  return 4 * kPi * double(t.r[i]) * t.r[i];
}

AreaSample sample_sphere_area(const glm::dvec3& c, double r, double u1, double u2) {
  glm::dvec3 n = sample_uniform_sphere(u1, u2);
  return {c + n * r, n};
}

std::optional<SubtendedSample> sample_sphere_cone(const glm::dvec3& c, double r,
                                                  const glm::dvec3& ref, double u1, double u2) {
  double d2 = length_squared(c - ref);
  if (!(d2 > r * r)) return std::nullopt;
  double d = std::sqrt(d2), omc = cone_one_minus_cos(r * r, d2);
  glm::dvec3 local = sample_uniform_cone(u1, u2, omc);
  double sin2 = local.x * local.x + local.y * local.y;
  // The nearer root of the ray from ref along the sampled direction.
  double t_hit = d * local.z - std::sqrt(std::max(0.0, r * r - d2 * sin2));
  return SubtendedSample{Frame((c - ref) / d).to_world(local), t_hit, 2 * kPi * omc};
}

std::optional<double> sphere_cone_solid_angle(const glm::dvec3& c, double r,
                                              const glm::dvec3& ref) {
  double d2 = length_squared(c - ref);
  if (!(d2 > r * r)) return std::nullopt;
  return 2 * kPi * cone_one_minus_cos(r * r, d2);
}

AreaSample Sphere::sample_area(const Table& t, uint32_t i, double, double u1, double u2) {
  return sample_sphere_area(glm::dvec3(t.center(i)), t.r[i], u1, u2);
}

std::optional<SubtendedSample> Sphere::sample_subtended(const Table& t, uint32_t i,
                                                        const glm::dvec3& ref, double u1,
                                                        double u2) {
  return sample_sphere_cone(glm::dvec3(t.center(i)), t.r[i], ref, u1, u2);
}

std::optional<double> Sphere::subtended_solid_angle(const Table& t, uint32_t i,
                                                    const glm::dvec3& ref) {
  return sphere_cone_solid_angle(glm::dvec3(t.center(i)), t.r[i], ref);
}

}  // namespace raylane
