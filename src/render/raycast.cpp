#include "raylane/render/raycast.h"

#include <cmath>

#include "raylane/core/float_util.h"

namespace raylane {

namespace {

constexpr std::string_view kModeNames[] = {"normal", "depth", "albedo", "id", "lit"};
constexpr uint32_t kTile = 4;  // camera rays go out in 4×4 tiles: one AVX-512 packet each

Vec3d to_d(const Vec3f& v) {
  return Vec3d(v);
}

const Material& material_of(const Scene& scene, const Hit& hit) {
  return scene.materials[scene.material_of(hit.prim)];
}

Vec3d shade_simple(const Scene& scene, RaycastMode mode, const Hit& hit) {
  if (!hit.hit()) return {0, 0, 0};
  switch (mode) {
    case RaycastMode::kNormal:
      return (hit.surface.ns + Vec3d(1, 1, 1)) * 0.5;
    case RaycastMode::kDepth:
      return {hit.t, hit.t, hit.t};
    case RaycastMode::kAlbedo:
      return to_d(material_of(scene, hit).kd);
    case RaycastMode::kId:
      return {double(uint32_t(hit.prim.tag()) + 1), double(hit.prim.row()), 0.0};
    case RaycastMode::kLit:
      break;
  }
  return {0, 0, 0};
}

// One shadow ray of the lit mode: from a shaded pixel towards an emitting sphere's centre.
struct ShadowQuery {
  std::size_t pixel;
  PrimRef light;
  Vec3d contribution;  // what the pixel gains if the light's centre is visible
};

// The course's first shading: ambient·Kd, plus for each emitting sphere whose centre is
// visible, Le·(Kd·max(0, N·L) + Ks·max(0, R·V)^α), R = L mirrored about N (Phong 1975).
// Returns the ambient (or emitted) part and appends the shadow queries of the rest.
Vec3d shade_lit_begin(const Scene& scene, const Rayd& ray, const Hit& hit, std::size_t pixel,
                      std::vector<Rayd>& shadow_rays, std::vector<ShadowQuery>& queries) {
  if (!hit.hit()) return {0, 0, 0};
  const Material& m = material_of(scene, hit);
  if (m.is_light) return to_d(m.emission);
  Vec3d n = hit.front_face ? hit.surface.ns : -hit.surface.ns;
  Vec3d v = -normalize(ray.d);
  Vec3d origin = offset_ray_origin(hit.surface.p, hit_point_error(ray, hit.t), hit.surface.ng, v);
  for (PrimRef light : scene.lights) {
    if (light.tag() != PrimTag::kSphere) continue;
    Vec3d to_light = Vec3d(scene.table<Sphere>().center(light.row())) - origin;
    double dist = length(to_light);
    Vec3d l = to_light / dist;
    double nl = dot(n, l);
    if (!(nl > 0)) continue;
    Vec3d r = 2 * nl * n - l;
    double spec = std::pow(std::max(0.0, dot(r, v)), double(m.alpha));
    Vec3d le = to_d(scene.materials[scene.material_of(light)].emission);
    shadow_rays.push_back({origin, l, 0.0, dist});
    queries.push_back({pixel, light, le * (to_d(m.kd) * nl + to_d(m.ks) * spec)});
  }
  return to_d(scene.ambient) * to_d(m.kd);
}

// Camera rays for rows [y0, y0 + rows) of the pixel grid (y up), in 4×4 tiles; `pixel`
// receives each ray's image index (row 0 at the top).
void camera_rays(const Camera& cam, uint32_t y0, uint32_t rows, std::vector<Rayd>& rays,
                 std::vector<std::size_t>& pixel) {
  rays.clear();
  pixel.clear();
  for (uint32_t tx = 0; tx < cam.width; tx += kTile)
    for (uint32_t y = y0; y < y0 + rows; ++y)
      for (uint32_t x = tx; x < std::min(tx + kTile, cam.width); ++x) {
        rays.push_back(cam.ray_through(x + 0.5, y + 0.5));
        pixel.push_back(std::size_t(cam.height - 1 - y) * cam.width + x);
      }
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

Vec3d offset_ray_origin(const Vec3d& p, const Vec3d& p_error, const Vec3d& ng,
                        const Vec3d& toward) {
  Vec3d offset = ng * dot(abs(ng), p_error);
  if (dot(ng, toward) < 0) offset = -offset;
  Vec3d o = p + offset;
  // Round away from p so the offset is not lost to rounding (pbrt-v4 OffsetRayOrigin).
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0) o[i] = std::nextafter(o[i], INFINITY);
    if (offset[i] < 0) o[i] = std::nextafter(o[i], -INFINITY);
  }
  return o;
}

Vec3d hit_point_error(const Rayd& ray, double t) {
  constexpr double kBound = 32 * kFloatUnitRoundoff;
  return (abs(ray.o) + abs(ray.d * t)) * kBound;
}

Image render_raycast(const Tracer& tracer, RaycastMode mode, RaycastStats* stats) {
  const Scene& scene = tracer.scene();
  Camera camera = Camera::from_scene(scene);
  Image image(scene.width, scene.height);
  std::vector<Rayd> rays, shadow_rays;
  std::vector<std::size_t> pixel;
  std::vector<Hit> hits, shadow_hits;
  std::vector<ShadowQuery> queries;
  RaycastStats st;
  // Bands of 64 pixel rows: enough rays per batch to keep every thread busy.
  for (uint32_t y0 = 0; y0 < scene.height; y0 += 64) {
    uint32_t rows = std::min<uint32_t>(64, scene.height - y0);
    camera_rays(camera, y0, rows, rays, pixel);
    tracer.closest(rays, hits);
    st.camera_rays += rays.size();
    shadow_rays.clear();
    queries.clear();
    for (std::size_t i = 0; i < rays.size(); ++i) {
      Vec3d c = mode == RaycastMode::kLit
                    ? shade_lit_begin(scene, rays[i], hits[i], pixel[i], shadow_rays, queries)
                    : shade_simple(scene, mode, hits[i]);
      for (int k = 0; k < 3; ++k)
        image.rgb[pixel[i] * 3 + k] = float(c[k]);
    }
    if (shadow_rays.empty()) continue;
    // Shadow rays as closest-hit queries: the light is visible when the first thing met is
    // the light itself (no epsilon on the far end of the segment).
    tracer.closest(shadow_rays, shadow_hits);
    st.shadow_rays += shadow_rays.size();
    for (std::size_t q = 0; q < queries.size(); ++q) {
      const Hit& h = shadow_hits[q];
      if (h.hit() && h.prim != queries[q].light) continue;
      for (int k = 0; k < 3; ++k)
        image.rgb[queries[q].pixel * 3 + k] += float(queries[q].contribution[k]);
    }
  }
  if (stats) *stats = st;
  return image;
}

}  // namespace raylane
