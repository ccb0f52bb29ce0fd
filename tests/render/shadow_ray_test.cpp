// Shadow rays as occlusion queries aimed at their light, ending at the light point
// (core/ray_offset.h, shadow_ray_tmax; Tracer::occluded): the light's own surface must never
// block its sample — at any scale, far from the origin, grazing or not, for every kind of
// light — and a real occluder just in front of the light must. Traced the way the renderer
// traces them: origins offset off a surface, rays rounded to float, every instruction set, and
// the double reference tracer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "raylane/core/ray_offset.h"
#include "raylane/render/lights/lights.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sampling.h"
#include "raylane/scene/parser.h"
#include "raylane/trace/tracer.h"
#include "support/paths.h"

namespace raylane {
namespace {

// A scene of one light, `shape` scaled by `scale` about the origin and moved to `at`.
ParsedScene light_scene(const std::string& kind, std::vector<double> numbers, double scale,
                        const glm::dvec3& at, const std::string& extra = "") {
  static const std::string dir = [] {  // one triangle, for the mesh lights
    std::string d = testing::temp_dir();
    std::ofstream(d + "/shadow_tri.obj") << "v 0 0 0\nv 1 0 0\nv 0.2 1 0\nf 1 2 3\n";
    return d;
  }();
  std::ostringstream text;
  text.precision(17);
  text << "camera 0 0 0 1\nlight 1 1 1\n" << kind;
  if (kind == "mesh") text << " shadow_tri.obj";
  // Sphere: centre, radius. Box: corner, diagonal. Cylinder: base, axis, radius. Mesh: where
  // and how large. The first three numbers are a point, the rest lengths.
  for (std::size_t i = 0; i < numbers.size(); ++i)
    text << ' ' << (i < 3 ? at[int(i)] + numbers[i] * scale : numbers[i] * scale);
  text << '\n' << extra;
  return parse_scene(text.str(), dir + "/shadow.scn");
}

struct Shadows {
  std::vector<Rayd> rays;
  std::vector<PrimRef> aims;
  std::vector<double> cos_light;  // |cos| at the light point (1 for a sphere's cone sample)
};

// Light samples from random shading points around the light (within 4 light sizes), each
// from an origin offset off a random surface through the point, as the renderer makes them.
Shadows shadow_rays(const Scene& scene, double scale, const glm::dvec3& at, int count) {
  LightSampler lights(scene);
  Rng rng(23);
  Shadows out;
  while (int(out.rays.size()) < count) {
    glm::dvec3 p = at + glm::dvec3(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5) *
                            (8 * scale);
    LightSample s =
        lights.sample(p, rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform(), 0.5);
    if (!s.valid()) continue;
    glm::dvec3 ng = sample_uniform_sphere(rng.uniform(), rng.uniform());
    if (dot(ng, s.wi) < 0) ng = -ng;
    // The error bound of a point reached by a ray of length 2·scale (the renderer's bound).
    glm::dvec3 o = offset_ray_origin(p, hit_point_error({p, s.wi}, 2 * scale), ng, s.wi);
    out.rays.push_back({o, s.wi, 0, shadow_ray_tmax(o, p, s.wi, s.dist)});
    out.aims.push_back(s.light);
    out.cos_light.push_back(s.n == glm::dvec3(0, 0, 0) ? 1.0 : std::abs(dot(s.wi, s.n)));
  }
  return out;
}

// The packet tracer at every instruction set and the double reference: every ray blocked
// (1) or every ray clear (0).
void expect_every_tracer_says(const Scene& scene, const Bvh& bvh, const std::vector<Rayd>& rays,
                              const std::vector<PrimRef>& aims, uint8_t answer) {
  std::vector<Tracer> tracers;
  for (Isa isa : supported_isas())
    tracers.emplace_back(scene, bvh, TracerBackend::kPacket, isa);
  tracers.emplace_back(scene, bvh, TracerBackend::kBvh);
  for (const Tracer& tracer : tracers) {
    std::vector<uint8_t> blocked;
    TraceScratch scratch;
    tracer.occluded(rays, aims, blocked, scratch);
    for (std::size_t i = 0; i < rays.size(); ++i)
      ASSERT_EQ(blocked[i], answer) << "ray " << i << " tracer " << int(tracer.backend()) << " isa "
                                    << isa_name(tracer.isa());
  }
}

// No sample is blocked, with every tracer, though some are grazing (|cos| < 1e-3 at the light,
// where the ray's offset origin moves its crossing of the surface by much more than rounding).
void expect_light_never_blocks_itself(const std::string& kind, std::vector<double> numbers) {
  for (double scale : {1e-2, 1.0, 300.0})
    for (glm::dvec3 at : {glm::dvec3(0, 0, 0), glm::dvec3(1e4, -2e4, 5e3) * scale}) {
      SCOPED_TRACE(kind + " scale " + std::to_string(scale) + " at x " + std::to_string(at.x));
      ParsedScene parsed = light_scene(kind, numbers, scale, at);
      ASSERT_TRUE(parsed.ok()) << to_string(parsed.diagnostics.items.front());
      Bvh bvh = build_bvh_and_reorder(parsed.scene);
      Shadows s = shadow_rays(parsed.scene, scale, at, 20000);
      expect_every_tracer_says(parsed.scene, bvh, s.rays, s.aims, 0);
      if (kind != "sphere") {
        EXPECT_GT(std::count_if(s.cos_light.begin(), s.cos_light.end(),
                                [](double c) { return c < 1e-3; }),
                  0);
      }
    }
}

TEST(ShadowRays, TheLightNeverBlocksItsOwnSample) {
  expect_light_never_blocks_itself("sphere", {0.3, 0.2, 0.1, 0.8});
  expect_light_never_blocks_itself("box", {-0.5, -0.4, 0.2, 1.2, 0.8, 0.6});
  expect_light_never_blocks_itself("cylinder", {0.5, 0.2, 0.1, -0.6, 0.3, 0.9, 0.3});
  expect_light_never_blocks_itself("mesh", {-0.3, -0.4, 0.6, 1.2});
}

// A shell of another material around a sphere light, 1e-4 of the light's radius off its
// surface: every sample from outside is blocked.
TEST(ShadowRays, AnOccluderJustInFrontOfTheLightBlocks) {
  for (double scale : {1e-2, 1.0, 300.0}) {
    SCOPED_TRACE(scale);
    std::ostringstream shell;
    shell.precision(17);
    shell << "brdf 0.5 0.5 0.5 0 0 0 1 0 0 0 1\nsphere 0 0 0 " << 1.0001 * scale << '\n';
    ParsedScene parsed =
        light_scene("sphere", {0, 0, 0, 1}, scale, glm::dvec3(0, 0, 0), shell.str());
    ASSERT_TRUE(parsed.ok()) << to_string(parsed.diagnostics.items.front());
    Bvh bvh = build_bvh_and_reorder(parsed.scene);
    LightSampler lights(parsed.scene);
    Rng rng(29);
    std::vector<Rayd> rays;
    std::vector<PrimRef> aims;
    while (rays.size() < 2000) {
      glm::dvec3 p = sample_uniform_sphere(rng.uniform(), rng.uniform()) * (scale * 1.5);
      LightSample s =
          lights.sample(p, rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform(), 0.5);
      if (!s.valid()) continue;
      rays.push_back({p, s.wi, 0, shadow_ray_tmax(p, p, s.wi, s.dist)});
      aims.push_back(s.light);
    }
    expect_every_tracer_says(parsed.scene, bvh, rays, aims, 1);
  }
}

}  // namespace
}  // namespace raylane
