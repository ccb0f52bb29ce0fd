#include "raylane/render/lights.h"

#include <algorithm>
#include <cmath>

#include "raylane/render/sampling.h"

namespace raylane {

namespace {

struct AreaPoint {
  Vec3d p, n;  // n: unit outward normal
};

// Areas and uniform area sampling per kind. `u_part` picks a face of a box or a part of a
// cylinder in proportion to its area.
double area(const SphereTable& t, uint32_t i) {
  return 4 * kPi * double(t.r[i]) * t.r[i];
}
double area(const BoxTable& t, uint32_t i) {
  Vec3d d = Vec3d(t.hi(i)) - Vec3d(t.lo(i));
  return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
}
double area(const CylinderTable& t, uint32_t i) {
  double r = t.r[i];
  return 2 * kPi * r * length(Vec3d(t.axis(i))) + 2 * kPi * r * r;
}
double area(const TriangleTable& t, uint32_t i) {
  return 0.5 * length(cross(Vec3d(t.p1(i)) - Vec3d(t.p0(i)), Vec3d(t.p2(i)) - Vec3d(t.p0(i))));
}

AreaPoint sample_area(const SphereTable& t, uint32_t i, double, double u1, double u2) {
  Vec3d n = sample_uniform_sphere(u1, u2);
  return {Vec3d(t.center(i)) + n * double(t.r[i]), n};
}

AreaPoint sample_area(const BoxTable& t, uint32_t i, double u_part, double u1, double u2) {
  Vec3d lo(t.lo(i)), hi(t.hi(i)), d = hi - lo;
  double face[3] = {d.y * d.z, d.z * d.x, d.x * d.y};  // faces normal to x, y, z (each ×2)
  double pick = u_part * 2 * (face[0] + face[1] + face[2]);
  int axis = 0;
  while (axis < 2 && pick >= 2 * face[axis])
    pick -= 2 * face[axis++];
  bool high = pick >= face[axis];
  int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  Vec3d p, n(0, 0, 0);
  p[axis] = high ? hi[axis] : lo[axis];
  p[a1] = lo[a1] + u1 * d[a1];
  p[a2] = lo[a2] + u2 * d[a2];
  n[axis] = high ? 1 : -1;
  return {p, n};
}

AreaPoint sample_area(const CylinderTable& t, uint32_t i, double u_part, double u1, double u2) {
  Vec3d axis(t.axis(i)), base(t.base(i));
  double h = length(axis), r = t.r[i];
  Frame f(axis / h);
  double side = 2 * kPi * r * h, cap = kPi * r * r;
  double pick = u_part * (side + 2 * cap), phi = 2 * kPi * u2;
  Vec3d radial = f.s * std::cos(phi) + f.t * std::sin(phi);
  if (pick < side) return {base + f.n * (u1 * h) + radial * r, radial};
  bool top = pick >= side + cap;
  return {base + (top ? axis : Vec3d(0, 0, 0)) + radial * (r * std::sqrt(u1)), top ? f.n : -f.n};
}

AreaPoint sample_area(const TriangleTable& t, uint32_t i, double, double u1, double u2) {
  Vec3d p0(t.p0(i)), p1(t.p1(i)), p2(t.p2(i));
  double su = std::sqrt(u1), b0 = 1 - su, b1 = u2 * su;  // uniform barycentrics
  return {p0 * b0 + p1 * b1 + p2 * (1 - b0 - b1), normalize(cross(p1 - p0, p2 - p0))};
}

// 1 − cos θmax of the cone a sphere subtends from distance² d2 > r², without cancellation.
double cone_one_minus_cos(double r2, double d2) {
  double sin2 = r2 / d2;
  return sin2 / (1 + std::sqrt(std::max(0.0, 1 - sin2)));
}

}  // namespace

LightSampler::LightSampler(const Scene& scene) : scene_(scene) {
  double total = 0;
  std::vector<double> power;
  for (PrimRef l : scene.lights) {
    Vec3d le(scene.materials[scene.material_of(l)].emission);
    double a =
        dispatch(l.tag(), [&](auto kind) { return area(scene.table<decltype(kind)>(), l.row()); });
    double w = (le.x + le.y + le.z) / 3 * a;
    if (!(w > 0) || !std::isfinite(w)) continue;
    lights_.push_back(l);
    power.push_back(w);
    total += w;
  }
  double acc = 0;
  for (std::size_t k = 0; k < lights_.size(); ++k) {
    acc += power[k] / total;
    cdf_.push_back(acc);
    choice_[lights_[k].bits()] = power[k] / total;
  }
  if (!cdf_.empty()) cdf_.back() = 1.0;
}

LightSample LightSampler::sample(const Vec3d& ref, double u_light, double u_part, double u1,
                                 double u2) const {
  LightSample s;
  if (lights_.empty()) return s;
  std::size_t k = std::upper_bound(cdf_.begin(), cdf_.end(), u_light) - cdf_.begin();
  k = std::min(k, lights_.size() - 1);
  PrimRef l = lights_[k];
  double choice = choice_.at(l.bits());
  s.light = l;
  s.le = Vec3d(scene_.materials[scene_.material_of(l)].emission);
  if (l.tag() == PrimTag::kSphere) {
    const SphereTable& t = scene_.table<Sphere>();
    Vec3d c(t.center(l.row()));
    double r = t.r[l.row()], d2 = length_squared(c - ref);
    if (d2 > r * r) {  // outside: uniform in the subtended cone (pbrt-v4 Sphere::Sample)
      double d = std::sqrt(d2), omc = cone_one_minus_cos(r * r, d2);
      Vec3d local = sample_uniform_cone(u1, u2, omc);
      Vec3d wi = Frame((c - ref) / d).to_world(local);
      double sin2 = local.x * local.x + local.y * local.y;
      double t_hit = d * local.z - std::sqrt(std::max(0.0, r * r - d2 * sin2));
      s.wi = wi;
      s.dist = t_hit;
      s.p = ref + wi * t_hit;
      s.pdf = choice / (2 * kPi * omc);
      return s;
    }
  }
  AreaPoint a = dispatch(l.tag(), [&](auto kind) {
    return sample_area(scene_.table<decltype(kind)>(), l.row(), u_part, u1, u2);
  });
  Vec3d to = a.p - ref;
  double d2 = length_squared(to);
  if (!(d2 > 0)) return s;
  s.dist = std::sqrt(d2);
  s.wi = to / s.dist;
  double cos_l = -dot(s.wi, a.n);
  if (l.tag() == PrimTag::kTriangle) cos_l = std::abs(cos_l);
  if (!(cos_l > 0)) return s;  // the back of a solid emitter
  double a_total =
      dispatch(l.tag(), [&](auto kind) { return area(scene_.table<decltype(kind)>(), l.row()); });
  s.p = a.p;
  s.pdf = choice * d2 / (cos_l * a_total);
  if (!std::isfinite(s.pdf)) s.pdf = 0;
  return s;
}

double LightSampler::pdf(const Vec3d& ref, const Vec3d& wi, const Hit& hit) const {
  auto it = choice_.find(hit.prim.bits());
  if (it == choice_.end()) return 0;
  PrimRef l = hit.prim;
  if (l.tag() == PrimTag::kSphere) {
    const SphereTable& t = scene_.table<Sphere>();
    double r = t.r[l.row()], d2 = length_squared(Vec3d(t.center(l.row())) - ref);
    if (d2 > r * r) return it->second / (2 * kPi * cone_one_minus_cos(r * r, d2));
  }
  double d2 = length_squared(hit.surface.p - ref);
  double cos_l = std::abs(dot(wi, hit.surface.ng));
  if (l.tag() != PrimTag::kTriangle && !hit.front_face) return 0;
  if (!(cos_l > 0)) return 0;
  double a_total =
      dispatch(l.tag(), [&](auto kind) { return area(scene_.table<decltype(kind)>(), l.row()); });
  return it->second * d2 / (cos_l * a_total);
}

Vec3d LightSampler::emitted(const Hit& hit) const {
  const Material& m = scene_.materials[scene_.material_of(hit.prim)];
  if (!m.is_light) return {0, 0, 0};
  if (hit.prim.tag() != PrimTag::kTriangle && !hit.front_face) return {0, 0, 0};
  return Vec3d(m.emission);
}

}  // namespace raylane
