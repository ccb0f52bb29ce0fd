// Triangles as emitters: area and area sampling, prims/triangle_light.h's steps at double.
#include "raylane/prims/triangle.h"

#include "raylane/prims/triangle_light.h"

namespace raylane {

namespace {
TriangleLightPoint<double, glm::dvec3> light_point(const TriangleTable& t, uint32_t i, double u1,
                                                   double u2) {
  return triangle_light_point<double>(glm::dvec3(t.p0(i)), glm::dvec3(t.p1(i)), glm::dvec3(t.p2(i)),
                                      u1, u2);
}
}  // namespace

double Triangle::area(const Table& t, uint32_t i) {
  return light_point(t, i, 0.5, 0.5).area;
}

AreaSample Triangle::sample_area(const Table& t, uint32_t i, double, double u1, double u2) {
  const TriangleLightPoint<double, glm::dvec3> x = light_point(t, i, u1, u2);
  return {x.p, x.n};
}

}  // namespace raylane
