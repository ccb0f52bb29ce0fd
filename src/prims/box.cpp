// Boxes as emitters: area and area sampling.
#include "raylane/prims/box.h"

#include "raylane/prims/box_faces.h"

namespace raylane {

double Box::area(const Table& t, uint32_t i) {
  glm::dvec3 d = glm::dvec3(t.hi(i)) - glm::dvec3(t.lo(i));
  return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

AreaSample Box::sample_area(const Table& t, uint32_t i, double u_part, double u1, double u2) {
  glm::dvec3 lo(t.lo(i)), hi(t.hi(i)), d = hi - lo;
  double face[3] = {d.y * d.z, d.z * d.x, d.x * d.y};  // faces normal to x, y, z (each ×2)
  double pick = u_part * 2 * (face[0] + face[1] + face[2]);
  int axis = 0;
  while (axis < 2 && pick >= 2 * face[axis])
    pick -= 2 * face[axis++];
  bool high = pick >= face[axis];
  int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  glm::dvec3 p, n(0, 0, 0);
  p[axis] = high ? hi[axis] : lo[axis];
  p[a1] = lo[a1] + u1 * d[a1];
  p[a2] = lo[a2] + u2 * d[a2];
  n[axis] = high ? 1 : -1;
  return {p, n};
}

namespace {

BoxFacePoint<double, glm::dvec3> face_point(const BoxTable& t, uint32_t i, const glm::dvec3& ref,
                                            double u_part, double u1, double u2) {
  return box_face_point<double>(glm::dvec3(t.lo(i)), glm::dvec3(t.hi(i)), ref, u_part, u1, u2);
}

}  // namespace

double Box::area_seen_from(const Table& t, uint32_t i, const glm::dvec3& ref) {
  return box_faces_seen<double>(glm::dvec3(t.lo(i)), glm::dvec3(t.hi(i)), ref).total();
}

AreaSample Box::sample_area_seen_from(const Table& t, uint32_t i, const glm::dvec3& ref,
                                      double u_part, double u1, double u2) {
  const BoxFacePoint<double, glm::dvec3> f = face_point(t, i, ref, u_part, u1, u2);
  if (!(f.area > 0)) return {ref, {0, 0, 0}};
  return {f.p, f.n};
}

}  // namespace raylane
