#include "raylane/render/raycast.h"

#include <cmath>

#include "raylane/core/float_util.h"
#include "raylane/trace/brute_force.h"

namespace raylane {

namespace {

constexpr std::string_view kModeNames[] = {"normal", "depth", "albedo", "id", "lit"};

Vec3d to_d(const Vec3f& v) {
  return Vec3d(v);
}

// The course's first shading: ambient·Kd, plus for each emitting sphere whose centre is
// visible, Le·(Kd·max(0, N·L) + Ks·max(0, R·V)^α), R = L mirrored about N (Phong 1975).
Vec3d shade_lit(const Scene& scene, const ReferenceTracer& tracer, const Rayd& ray, const Hit& hit,
                uint64_t* shadow_rays) {
  const Material& m = scene.materials[scene.material_of(hit.prim)];
  if (m.is_light) return to_d(m.emission);
  Vec3d n = hit.front_face ? hit.surface.ns : -hit.surface.ns;
  Vec3d v = -normalize(ray.d);
  Vec3d color = to_d(scene.ambient) * to_d(m.kd);
  Vec3d origin =
      offset_ray_origin(hit.surface.p, reference_point_error(ray, hit.t), hit.surface.ng, v);
  for (PrimRef light : scene.lights) {
    if (light.tag() != PrimTag::kSphere) continue;
    Vec3d c(scene.table<Sphere>().center(light.row()));
    Vec3d to_light = c - origin;
    double dist = length(to_light);
    Vec3d l = to_light / dist;
    double nl = dot(n, l);
    if (nl <= 0) continue;
    if (shadow_rays) ++*shadow_rays;
    Hit blocker = tracer.closest({origin, l, 0.0, dist});
    if (blocker.hit() && blocker.prim != light) continue;
    Vec3d r = 2 * nl * n - l;
    double spec = std::pow(std::max(0.0, dot(r, v)), double(m.alpha));
    Vec3d le = to_d(scene.materials[scene.material_of(light)].emission);
    color += le * (to_d(m.kd) * nl + to_d(m.ks) * spec);
  }
  return color;
}

}  // namespace

std::optional<RaycastMode> raycast_mode_from_name(std::string_view name) {
  for (int i = 0; i < 5; ++i)
    if (name == kModeNames[i]) return RaycastMode(i);
  return std::nullopt;
}

std::string_view raycast_mode_name(RaycastMode mode) {
  return kModeNames[int(mode)];
}

Hit ReferenceTracer::closest(const Rayd& ray) const {
  return closest_hit_ref(scene, ray);
}
bool ReferenceTracer::occluded(const Rayd& ray) const {
  return any_hit_ref(scene, ray);
}

Vec3d offset_ray_origin(const Vec3d& p, const Vec3d& p_error, const Vec3d& ng,
                        const Vec3d& toward) {
  double d = dot(abs(ng), p_error);
  Vec3d offset = ng * d;
  if (dot(ng, toward) < 0) offset = -offset;
  Vec3d o = p + offset;
  // Round away from p so the offset is not lost to rounding (pbrt-v4 OffsetRayOrigin).
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0) o[i] = std::nextafter(o[i], INFINITY);
    if (offset[i] < 0) o[i] = std::nextafter(o[i], -INFINITY);
  }
  return o;
}

Vec3d reference_point_error(const Rayd& ray, double t) {
  constexpr double kBound = 64 * kDoubleUnitRoundoff;
  return (abs(ray.o) + abs(ray.d * t)) * kBound;
}

Vec3d shade_raycast(const Scene& scene, const ReferenceTracer& tracer, RaycastMode mode,
                    const Rayd& ray, uint64_t* shadow_rays) {
  Hit hit = tracer.closest(ray);
  if (!hit.hit()) return {0, 0, 0};
  switch (mode) {
    case RaycastMode::kNormal:
      return (hit.surface.ns + Vec3d(1, 1, 1)) * 0.5;
    case RaycastMode::kDepth:
      return {hit.t, hit.t, hit.t};
    case RaycastMode::kAlbedo:
      return to_d(scene.materials[scene.material_of(hit.prim)].kd);
    case RaycastMode::kId:
      return {double(uint32_t(hit.prim.tag()) + 1), double(hit.prim.row()), 0.0};
    case RaycastMode::kLit:
      return shade_lit(scene, tracer, ray, hit, shadow_rays);
  }
  return {0, 0, 0};
}

Image render_raycast(const Scene& scene, const ReferenceTracer& tracer, RaycastMode mode,
                     RaycastStats* stats) {
  Camera camera = Camera::from_scene(scene);
  Image image(scene.width, scene.height);
  uint64_t shadow_rays = 0;
  const int height = int(scene.height);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : shadow_rays)
  for (int y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < scene.width; ++x) {
      Rayd ray = camera.ray_through(x + 0.5, y + 0.5);
      Vec3d c = shade_raycast(scene, tracer, mode, ray, &shadow_rays);
      image.set(x, scene.height - 1 - uint32_t(y), Vec3f(c));  // row 0 is the top
    }
  }
  if (stats) {
    stats->camera_rays = uint64_t(scene.width) * scene.height;
    stats->shadow_rays = shadow_rays;
  }
  return image;
}

}  // namespace raylane
