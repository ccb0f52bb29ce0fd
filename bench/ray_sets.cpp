#include "ray_sets.h"

#include <cmath>
#include <map>
#include <mutex>
#include <random>

#include "raylane/core/ray_offset.h"
#include "raylane/render/camera/camera.h"
#include "raylane/trace/tracer.h"

namespace raylane::bench {

namespace {

constexpr uint32_t kTile = 4;

// One ray per pixel centre, in 4×4 tiles (tiles row-major, pixels row-major inside a tile),
// as the ray-set format stores camera rays (docs/ray-sets.md).
std::vector<Rayd> primary_rays(const Scene& scene) {
  Camera cam = Camera::from_scene(scene);
  std::vector<Rayd> rays;
  rays.reserve(std::size_t(cam.width) * cam.height);
  for (uint32_t ty = 0; ty < cam.height; ty += kTile)
    for (uint32_t tx = 0; tx < cam.width; tx += kTile)
      for (uint32_t y = ty; y < std::min(ty + kTile, cam.height); ++y)
        for (uint32_t x = tx; x < std::min(tx + kTile, cam.width); ++x)
          rays.push_back(cam.ray_through(x + 0.5, cam.height - 1 - y + 0.5));
  return rays;
}

// The primary rays rounded to float (what every tracer is given) and their hits.
struct PrimaryHits {
  std::vector<Rayd> rays;
  std::vector<Hit> hits;
};

PrimaryHits primary_hits(const BenchScene& b) {
  PrimaryHits p;
  for (const Rayd& r : primary_rays(b.scene))
    p.rays.push_back(ray_cast<double>(ray_cast<float>(r)));
  Tracer tracer(b.scene, b.bvh, TracerBackend::kPacket);
  tracer.closest(p.rays, p.hits);
  return p;
}

// The surface side a new ray leaves from: the geometric normal turned toward the viewer.
glm::dvec3 facing_normal(const Hit& h, const Rayd& ray) {
  return dot(h.surface.ng, ray.d) < 0 ? h.surface.ng : -h.surface.ng;
}

glm::dvec3 cosine_direction(const glm::dvec3& n, double u1, double u2) {
  glm::dvec3 a = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  glm::dvec3 t = normalize(cross(n, a)), s = cross(n, t);
  double r = std::sqrt(u1), phi = 2 * M_PI * u2;
  return normalize(t * (r * std::cos(phi)) + s * (r * std::sin(phi)) +
                   n * std::sqrt(std::max(0.0, 1 - u1)));
}

RaySet make_set(const BenchScene& b, RayKind kind) {
  RaySet set;
  set.occlusion = kind == RayKind::kShadow;
  if (kind == RayKind::kPrimary) {
    set.rays = RayStream::from(primary_rays(b.scene));
    return set;
  }
  PrimaryHits p = primary_hits(b);
  std::mt19937_64 rng(kind == RayKind::kShadow ? 1 : 2);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Rayd> rays;
  for (std::size_t i = 0; i < p.rays.size(); ++i) {
    const Hit& h = p.hits[i];
    if (!h.hit()) continue;
    glm::dvec3 n = facing_normal(h, p.rays[i]);
    glm::dvec3 dir = kind == RayKind::kShadow ? normalize(b.light - h.surface.p)
                                              : cosine_direction(n, u(rng), u(rng));
    glm::dvec3 o =
        offset_ray_origin(h.surface.p, hit_point_error(p.rays[i], h.t), h.surface.ng, dir);
    double tmax = kind == RayKind::kShadow ? length(b.light - o) - b.light_gap
                                           : std::numeric_limits<double>::infinity();
    rays.push_back({o, dir, 0.0, tmax});
  }
  set.rays = RayStream::from(rays);
  return set;
}

}  // namespace

const char* ray_kind_name(RayKind kind) {
  return kind == RayKind::kPrimary ? "primary" : kind == RayKind::kShadow ? "shadow" : "diffuse";
}

const RaySet& bench_rays(const BenchScene& b, RayKind kind) {
  static std::mutex mutex;
  static std::map<std::pair<const BenchScene*, RayKind>, RaySet> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto key = std::make_pair(&b, kind);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  return cache.emplace(key, make_set(b, kind)).first->second;
}

}  // namespace raylane::bench
