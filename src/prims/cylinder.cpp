// Capped cylinders as emitters: area and area sampling, over all of it and over what a point
// sees (prims/cylinder_light.h's steps at double).
#include <cmath>

#include "raylane/core/fast_math.h"
#include "raylane/core/warps.h"
#include "raylane/prims/cylinder.h"
#include "raylane/prims/cylinder_light.h"

namespace raylane {

double Cylinder::area(const Table& t, uint32_t i) {
  double r = t.r[i];
  return 2 * kPi * r * length(glm::dvec3(t.axis(i))) + 2 * kPi * r * r;
}

AreaSample Cylinder::sample_area(const Table& t, uint32_t i, double u_part, double u1, double u2) {
  glm::dvec3 axis(t.axis(i)), base(t.base(i));
  double h = length(axis), r = t.r[i];
  Frame f(axis / h);
  double side = 2 * kPi * r * h, cap = kPi * r * r;
  double pick = u_part * (side + 2 * cap);
  SinCos phi = sincos_2pi(u2);
  glm::dvec3 radial = f.s * phi.cos + f.t * phi.sin;
  if (pick < side) return {base + f.n * (u1 * h) + radial * r, radial};
  bool top = pick >= side + cap;
  return {base + (top ? axis : glm::dvec3(0, 0, 0)) + radial * (r * std::sqrt(u1)),
          top ? f.n : -f.n};
}

double Cylinder::area_seen_from(const Table& t, uint32_t i, const glm::dvec3& ref) {
  return cylinder_parts_seen<double>(glm::dvec3(t.base(i)), cylinder_axis<double>(t.axis(i)),
                                     double(t.r[i]), ref)
      .total();
}

AreaSample Cylinder::sample_area_seen_from(const Table& t, uint32_t i, const glm::dvec3& ref,
                                           double u_part, double u1, double u2) {
  const CylinderLightPoint<double, glm::dvec3> x = cylinder_light_point<double>(
      glm::dvec3(t.base(i)), t.axis(i), double(t.r[i]), ref, u_part, u1, u2);
  if (!(x.area > 0)) return {ref, {0, 0, 0}};
  return {x.p, x.n};
}

}  // namespace raylane
