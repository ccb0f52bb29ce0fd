// Spheres as emitters: area, area sampling and sampling of the subtended cone.
#include "raylane/prims/sphere.h"
#include "raylane/core/warps.h"
#include "raylane/prims/sphere_cone.h"

namespace raylane {

double Sphere::area(const Table& t, uint32_t i) {
  return 4 * kPi * double(t.r[i]) * t.r[i];
}

AreaSample sample_sphere_area(const glm::dvec3& c, double r, double u1, double u2) {
  glm::dvec3 n = sample_uniform_sphere(u1, u2);
  return {c + n * r, n};
}

std::optional<SubtendedSample> sample_sphere_cone(const glm::dvec3& c, double r,
                                                  const glm::dvec3& ref, double u1, double u2) {
  const SphereCone<double, glm::dvec3> s = sphere_cone<double>(c, r, ref, u1, u2);
  if (!(s.solid_angle > 0)) return std::nullopt;  // ref is not outside the sphere
  return SubtendedSample{s.wi, s.dist, s.solid_angle};
}

std::optional<double> sphere_cone_solid_angle(const glm::dvec3& c, double r,
                                              const glm::dvec3& ref) {
  // sphere_cone's test: outside, and a cone of some solid angle.
  const double d2 = length_squared(c - ref), solid_angle = 2 * kPi * cone_one_minus_cos(r * r, d2);
  if (!(d2 > r * r) || !(solid_angle > 0)) return std::nullopt;
  return solid_angle;
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
