#include "raylane/render/raycast.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "raylane/core/ray_offset.h"
#include "raylane/render/materials/texturing.h"

namespace raylane {

namespace {

constexpr uint32_t kTile = 4;   // camera rays go out in 4×4 tiles: one AVX-512 packet each
constexpr uint32_t kBand = 16;  // rows per band: the unit of work of one thread
static_assert(kBand % kTile == 0, "bands of whole 4×4 tiles keep the packets of one pass");

glm::dvec3 to_d(const glm::vec3& v) {
  return glm::dvec3(v);
}

const Material& material_of(const Scene& scene, const Hit& hit) {
  return scene.materials[scene.material_of(hit.prim)];
}

glm::dvec3 albedo(const Scene& scene, const Hit& hit) {
  return albedo_at(scene, hit.prim, hit.surface);
}

// A light's radiance at the hit, times its texture there.
glm::dvec3 radiance(const Scene& scene, const Hit& hit) {
  const Material& m = material_of(scene, hit);
  return to_d(m.emission) * texture_factor(scene, m, hit.prim, hit.surface);
}

glm::dvec3 shade_simple(const Scene& scene, RaycastMode mode, const Hit& hit) {
  if (!hit.hit()) return {0, 0, 0};
  switch (mode) {
    case RaycastMode::kNormal:
      return (hit.surface.ns + glm::dvec3(1, 1, 1)) * 0.5;
    case RaycastMode::kDepth:
      return {hit.t, hit.t, hit.t};
    case RaycastMode::kAlbedo:
      return albedo(scene, hit);
    case RaycastMode::kUv: {
      TexCoord t = texcoord_of(scene, hit.prim, hit.surface);
      return {t.u, t.v, 0};
    }
    case RaycastMode::kPosition:
      return hit.surface.p;
    case RaycastMode::kId:
      return {double(uint32_t(hit.prim.tag()) + 1), double(hit.prim.row()), 0.0};
    case RaycastMode::kLit:
      break;
  }
  return {0, 0, 0};
}

// Where the lit view places a light: the point its kind names (a sphere's centre), if any.
std::optional<glm::dvec3> point_light(const Scene& scene, PrimRef light) {
  return dispatch(light.tag(), [&](auto kind) -> std::optional<glm::dvec3> {
    using Kind = decltype(kind);
    const auto& table = scene.table<Kind>();
    if constexpr (requires { Kind::point_light(table, light.row()); })
      return Kind::point_light(table, light.row());
    return std::nullopt;
  });
}

// One shadow ray of the lit mode: from a shaded pixel towards an emitting sphere's centre.
struct ShadowQuery {
  std::size_t pixel;
  PrimRef light;
  glm::dvec3 contribution{};  // what the pixel gains if the light's centre is visible
};

// The course's first shading: ambient·Kd, plus for each emitting sphere whose centre is
// visible, Le·(Kd·max(0, N·L) + Ks·max(0, R·V)^α), R = L mirrored about N (Phong 1975).
// Returns the ambient (or emitted) part and appends the shadow queries of the rest.
glm::dvec3 shade_lit_begin(const Tracer& tracer, const Rayd& ray, const Hit& hit, std::size_t pixel,
                           std::vector<Rayd>& shadow_rays, std::vector<ShadowQuery>& queries) {
  const Scene& scene = tracer.scene();
  if (!hit.hit()) return {0, 0, 0};
  const Material& m = material_of(scene, hit);
  if (m.is_light) return radiance(scene, hit);
  const glm::dvec3 kd = albedo(scene, hit);
  glm::dvec3 n = hit.front_face ? hit.surface.ns : -hit.surface.ns;
  glm::dvec3 v = -normalize(ray.d);
  glm::dvec3 origin =
      offset_ray_origin(hit.surface.p, tracer.hit_point_bound(ray, hit), hit.surface.ng, v);
  for (PrimRef light : scene.lights) {
    std::optional<glm::dvec3> at = point_light(scene, light);
    if (!at) continue;
    glm::dvec3 to_light = *at - origin;
    double dist = length(to_light);
    glm::dvec3 l = to_light / dist;
    double nl = dot(n, l);
    if (!(nl > 0)) continue;
    glm::dvec3 r = 2 * nl * n - l;
    double spec = std::pow(std::max(0.0, dot(r, v)), double(m.alpha));
    glm::dvec3 le = to_d(scene.materials[scene.material_of(light)].emission);
    shadow_rays.push_back({origin, l, 0.0, dist});
    queries.push_back({pixel, light, le * (kd * nl + to_d(m.ks) * spec)});
  }
  return to_d(scene.ambient) * kd;
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

// One band of rows: camera rays, shading, then the lit mode's shadow rays.
// `image` holds the region's pixels alone when there is one (region_slot).
void render_band(const Tracer& tracer, const Camera& camera, RaycastMode mode, uint32_t y0,
                 uint32_t rows, const std::optional<PixelRegion>& region, Image& image,
                 RaycastStats& st) {
  const Scene& scene = tracer.scene();
  std::vector<Rayd> rays, shadow_rays;
  std::vector<std::size_t> pixel;
  std::vector<Hit> hits, shadow_hits;
  std::vector<ShadowQuery> queries;
  camera_rays(camera, y0, rows, rays, pixel);
  tracer.closest(rays, hits);
  st.camera_rays += rays.size();
  for (std::size_t i = 0; i < rays.size(); ++i) {
    glm::dvec3 c = mode == RaycastMode::kLit
                       ? shade_lit_begin(tracer, rays[i], hits[i], pixel[i], shadow_rays, queries)
                       : shade_simple(scene, mode, hits[i]);
    const std::size_t at = region_slot(region, scene.width, pixel[i]);
    if (at == kNotInRegion) continue;
    for (int k = 0; k < 3; ++k)
      image.rgb[at * 3 + k] = float(c[k]);
  }
  if (shadow_rays.empty()) return;
  // Shadow rays as closest-hit queries: the light is visible when the first thing met is
  // the light itself (no epsilon on the far end of the segment).
  tracer.closest(shadow_rays, shadow_hits);
  st.shadow_rays += shadow_rays.size();
  for (std::size_t q = 0; q < queries.size(); ++q) {
    const Hit& h = shadow_hits[q];
    if (h.hit() && h.prim != queries[q].light) continue;
    const std::size_t at = region_slot(region, scene.width, queries[q].pixel);
    if (at == kNotInRegion) continue;
    for (int k = 0; k < 3; ++k)
      image.rgb[at * 3 + k] += float(queries[q].contribution[k]);
  }
}

}  // namespace

Image viewable(const Image& raw, RaycastMode mode) {
  if (mode != RaycastMode::kDepth && mode != RaycastMode::kId) return raw;
  Image out = raw;
  const std::size_t pixels = std::size_t(raw.width) * raw.height;
  if (mode == RaycastMode::kDepth) {
    float lo = std::numeric_limits<float>::infinity(), hi = 0;
    for (std::size_t i = 0; i < pixels; ++i)
      if (raw.rgb[3 * i] > 0) lo = std::min(lo, raw.rgb[3 * i]), hi = std::max(hi, raw.rgb[3 * i]);
    float range = hi > lo ? hi - lo : 1;
    for (std::size_t i = 0; i < pixels; ++i) {
      float t = raw.rgb[3 * i];
      float v = t > 0 ? 1 - 0.9f * (t - lo) / range : 0;
      out.rgb[3 * i] = out.rgb[3 * i + 1] = out.rgb[3 * i + 2] = v;
    }
    return out;
  }
  for (std::size_t i = 0; i < pixels; ++i) {
    uint32_t tag = uint32_t(raw.rgb[3 * i]), row = uint32_t(raw.rgb[3 * i + 1]);
    // A multiplicative hash (Knuth's 2654435761) spreads neighbouring rows over the colours.
    uint32_t h = (row * 2654435761u) ^ (tag * 0x9E3779B9u);
    for (int k = 0; k < 3; ++k)
      out.rgb[3 * i + k] = tag == 0 ? 0.0f : 0.2f + 0.8f * float((h >> (8 * k)) & 0xFF) / 255;
  }
  return out;
}

Image render_raycast(const Tracer& tracer, RaycastMode mode, RaycastStats* stats,
                     const std::optional<PixelRegion>& region) {
  const Scene& scene = tracer.scene();
  Camera camera = Camera::from_scene(scene);
  Image image =
      region ? Image(region->width(), region->height()) : Image(scene.width, scene.height);
  const std::ptrdiff_t bands = (scene.height + kBand - 1) / kBand;
  uint64_t camera_rays_total = 0, shadow_rays_total = 0;
  // Bands of rows over the threads; each band writes only its own pixels.
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : camera_rays_total, shadow_rays_total)
  for (std::ptrdiff_t b = 0; b < bands; ++b) {
    uint32_t y0 = uint32_t(b) * kBand, rows = std::min<uint32_t>(kBand, scene.height - y0);
    if (region && !region_meets_rows(*region, scene.height, y0, rows)) continue;
    RaycastStats st;
    render_band(tracer, camera, mode, y0, rows, region, image, st);
    camera_rays_total += st.camera_rays;
    shadow_rays_total += st.shadow_rays;
  }
  if (stats) *stats = {camera_rays_total, shadow_rays_total};
  return image;
}

}  // namespace raylane
