// Light sampling of every kind (docs/hard-cases.md M4, "triangle/area sampling"): two independent
// estimates of the same integrals must agree within 4σ.
//  - Irradiance-like ∫ cos θ · V(ω) dω over the light's emitting side, by next-event sampling
//    (cos/pdf) and by uniform directions ray-cast against the light (4π·cos·[front hit]).
//  - ∫ pdf dω over the sphere (uniform directions) = the fraction of valid samples.
// A moving light (mbsphere) at a path's time: sampled, hit and given its density where it is
// at that time.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "raylane/render/lights/lights.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sampling.h"
#include "raylane/scene/parser.h"
#include "support/estimate.h"
#include "support/paths.h"

namespace raylane {
namespace {

using testing::Estimate;
using testing::estimate;

// The nearest light hit by a ray, with the double reference kernels (the scene holds only
// lights).
constexpr double kInf = std::numeric_limits<double>::infinity();

Hit hit_light(const Scene& scene, const Rayd& ray) {
  Hit h;
  for (PrimRef light : scene.lights)
    dispatch(light.tag(), [&](auto kind) {
      const auto& table = scene.table<decltype(kind)>();
      double t = intersect_ref(table, light.row(), ray);
      if (!(t < h.t)) return;
      h.t = t;
      h.prim = light;
      h.surface = surface_ref(table, light.row(), ray, t);
      h.front_face = dot(ray.d, h.surface.ng) < 0;
    });
  return h;
}

// At `time`: the samples and the rays that check them (a moving light is where it is then).
void check_light(const std::string& shape_line, const glm::dvec3& ref, const glm::dvec3& n,
                 bool seen = true, double time = 0.5) {
  // Named as if in a folder holding tri.obj (one triangle), so `mesh` finds it.
  static const std::string dir = [] {
    std::string d = testing::temp_dir();
    std::ofstream(d + "/tri.obj") << "v 0 0 0\nv 1 0 0\nv 0.2 1 0\nf 1 2 3\n";
    return d;
  }();
  auto parsed = parse_scene("camera 0 0 0 1\nlight 1 1 1\n" + shape_line + "\n", dir + "/t.scn");
  ASSERT_TRUE(parsed.ok());
  const Scene& scene = parsed.scene;
  LightSampler lights(scene);
  Rng rng(17);
  const int count = 200000;
  int valid = 0;
  Estimate nee = estimate(count, [&] {
    double u[4] = {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
    LightSample s = lights.sample(ref, u[0], u[1], u[2], u[3], time);
    if (!s.valid()) return 0.0;
    ++valid;
    // The sample must lie on the light where a ray toward it first meets the light.
    Hit h = hit_light(scene, {ref, s.wi, 0, kInf, time});
    EXPECT_TRUE(h.hit());
    if (h.hit()) {
      EXPECT_NEAR(h.t, s.dist, 1e-6 * (1 + s.dist));
    }
    return std::abs(dot(s.wi, n)) / s.pdf;
  });
  Estimate uniform_cos = estimate(count, [&] {
    glm::dvec3 w = sample_uniform_sphere(rng.uniform(), rng.uniform());
    Hit h = hit_light(scene, {ref, w, 0, kInf, time});
    bool emits = h.hit() && (h.front_face || kind_two_sided(h.prim.tag()));
    return emits ? 4 * kPi * std::abs(dot(w, n)) : 0.0;
  });
  Estimate uniform_pdf = estimate(count, [&] {
    glm::dvec3 w = sample_uniform_sphere(rng.uniform(), rng.uniform());
    Hit h = hit_light(scene, {ref, w, 0, kInf, time});
    return h.hit() ? 4 * kPi * lights.pdf(ref, w, h, time) : 0.0;
  });
  SCOPED_TRACE(shape_line + " at time " + std::to_string(time));
  if (seen) {
    EXPECT_GT(uniform_cos.mean, 0.05);
  } else {  // nothing emitted toward ref: no valid sample either
    EXPECT_EQ(uniform_cos.mean, 0.0);
    EXPECT_EQ(valid, 0);
  }
  EXPECT_NEAR(nee.mean, uniform_cos.mean, 4 * std::hypot(nee.sigma, uniform_cos.sigma));
  double frac = double(valid) / count, frac_sigma = std::sqrt(frac * (1 - frac) / count);
  EXPECT_NEAR(uniform_pdf.mean, frac, 4 * std::hypot(uniform_pdf.sigma, frac_sigma));
}

TEST(Lights, EveryKindSamplesItsEmittingSurface) {
  glm::dvec3 ref(0.1, -0.2, 0.05), n = normalize(glm::dvec3(0.2, 0.1, 1));
  check_light("sphere 0.3 0.2 2 0.8", ref, n);            // outside: solid angle
  check_light("sphere 0.1 -0.2 0.3 0.5", ref, n, false);  // inside: emits outward only
  check_light("box -0.5 -0.4 1 1.2 0.8 0.6", ref, n);
  check_light("cylinder 0.5 0.2 1 -0.6 0.3 0.9 0.3", ref, n);
  // Two-sided triangles; seen from both sides. (Not the letter X: its two quads overlap in
  // one plane, so next-event sampling counts the overlap twice where a ray sees it once.)
  check_light("mesh tri.obj -0.3 -0.4 0.6 1.2 x 10", ref, n);
  check_light("mesh tri.obj -0.3 -0.4 0.6 1.2 x 190", ref, n);
  // Close to the surface, where cos/pdf varies strongly over the light: a warp that is not
  // uniform in area shows here.
  glm::dvec3 up(0, 0, 1);
  glm::dvec3 cap = glm::dvec3(0.5, 0.2, 1) - normalize(glm::dvec3(-0.6, 0.3, 0.9)) * 0.05;
  check_light("cylinder 0.5 0.2 1 -0.6 0.3 0.9 0.3", cap, normalize(glm::dvec3(-0.6, 0.3, 0.9)));
  check_light("box -0.5 -0.4 1 1.2 0.8 0.6", glm::dvec3(0.1, 0.1, 0.95), up);
  // A box seen on two faces and on three: the density counts the faces seen.
  check_light("box -0.5 -0.4 1 1.2 0.8 0.6", glm::dvec3(1.5, 0, 0.2), n);
  check_light("box -0.5 -0.4 1 1.2 0.8 0.6", glm::dvec3(-2, 1.5, 3), n);
  check_light("mesh tri.obj -0.3 -0.4 0.6 1.2", glm::dvec3(0.1, 0.1, 0.55), up);
  // A cylinder seen on its side alone (beside its middle, and 0.02 off its side) and on its
  // side and top cap: the density counts the parts seen. (0.3, 0.6, 0) is across its axis.
  const glm::dvec3 across = normalize(glm::dvec3(0.3, 0.6, 0));
  check_light("cylinder 0.5 0.2 1 -0.6 0.3 0.9 0.3", glm::dvec3(0.5, 0.95, 1.45), n);
  check_light("cylinder 0.5 0.2 1 -0.6 0.3 0.9 0.3", glm::dvec3(0.2, 0.35, 1.45) + 0.32 * across,
              across);
  check_light("cylinder 0.5 0.2 1 -0.6 0.3 0.9 0.3", glm::dvec3(-0.067, 1.234, 2.301), n);
}

// A sphere moving 3 units, seen from outside (its cone) and from inside (by area: ref is in
// the sphere at time 0.5, outside it at the ends), at times across the shutter.
TEST(Lights, AMovingLightIsSampledWhereItIsAtThePathsTime) {
  glm::dvec3 ref(0.1, -0.2, 0.05), n = normalize(glm::dvec3(0.2, 0.1, 1));
  for (double time : {0.0, 0.23, 0.5, 0.91}) {
    check_light("mbsphere -1.2 0.2 2 1.8 0.2 2 0.8", ref, n, true, time);
    check_light("mbsphere -1.4 -0.2 0.6 1.6 -0.2 0.6 0.7", ref, n, time < 0.3 || time > 0.7, time);
  }
}

// A box light is sampled on the faces that face the point alone: from any point outside it
// every sample is valid (sampling all six faces by area wastes those on the far side, about
// half), lies on a face whose outward normal faces the point, and is spread over those faces
// by their areas. From inside, no face faces the point and no sample is drawn.
TEST(Lights, ABoxLightIsSampledOnTheFacesThatFaceThePoint) {
  auto parsed =
      parse_scene("camera 0 0 0 1\nlight 1 1 1\nbox -0.5 -0.4 1 1.2 0.8 0.6\n", "box.scn");
  ASSERT_TRUE(parsed.ok());
  const LightSampler lights(parsed.scene);
  const glm::dvec3 lo(-0.5, -0.4, 1), hi(0.7, 0.4, 1.6);
  Rng rng(5);
  // Below the box (one face), beside and below (two), off a corner (three), inside (none).
  for (const glm::dvec3 ref : {glm::dvec3(0.1, 0, 0), glm::dvec3(1.5, 0, 0.2),
                               glm::dvec3(-2, 1.5, 3), glm::dvec3(0.1, 0, 1.3)}) {
    SCOPED_TRACE("from (" + std::to_string(ref.x) + ", " + std::to_string(ref.y) + ", " +
                 std::to_string(ref.z) + ")");
    bool inside = true;
    for (int k = 0; k < 3; ++k)
      inside = inside && ref[k] > lo[k] && ref[k] < hi[k];
    double faces[3] = {0, 0, 0};  // samples per axis of the face they lie on
    const int count = 20000;
    for (int i = 0; i < count; ++i) {
      LightSample s =
          lights.sample(ref, rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform(), 0.5);
      if (inside) {
        EXPECT_FALSE(s.valid());
        continue;
      }
      ASSERT_TRUE(s.valid());
      EXPECT_GT(dot(s.n, ref - s.p), 0);
      for (int k = 0; k < 3; ++k)
        faces[k] += s.n[k] != 0;
    }
    if (inside) continue;
    // Each face's share of the samples is its share of the faces' area seen, within 4 σ.
    const glm::dvec3 d = hi - lo;
    double area[3] = {0, 0, 0}, total = 0;
    for (int k = 0; k < 3; ++k) {
      if (ref[k] > hi[k] || ref[k] < lo[k]) area[k] = d[(k + 1) % 3] * d[(k + 2) % 3];
      total += area[k];
    }
    for (int k = 0; k < 3; ++k) {
      const double p = area[k] / total, sigma = std::sqrt(p * (1 - p) / count);
      EXPECT_NEAR(faces[k] / count, p, 4 * sigma + 1e-12) << "axis " << k;
    }
  }
}

}  // namespace
}  // namespace raylane
