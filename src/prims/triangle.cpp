// Triangles as emitters: area and area sampling.
#include <cmath>

#include "raylane/prims/triangle.h"

namespace raylane {

double Triangle::area(const Table& t, uint32_t i) {
  return 0.5 * length(cross(glm::dvec3(t.p1(i)) - glm::dvec3(t.p0(i)),
                            glm::dvec3(t.p2(i)) - glm::dvec3(t.p0(i))));
}

AreaSample Triangle::sample_area(const Table& t, uint32_t i, double, double u1, double u2) {
  glm::dvec3 p0(t.p0(i)), p1(t.p1(i)), p2(t.p2(i));
  double su = std::sqrt(u1), b0 = 1 - su, b1 = u2 * su;  // uniform barycentrics
  return {p0 * b0 + p1 * b1 + p2 * (1 - b0 - b1), normalize(cross(p1 - p0, p2 - p0))};
}

}  // namespace raylane
