// The scenes and rays the Tracer's tests share (tracer_test.cpp, surface_columns_test.cpp): the
// course scene's room with moving spheres, CSG and SDF blocks added, random rays through it, and
// with_every_tracer, which runs a check with the packet tracer at every instruction set and with
// the double references.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "raylane/core/warps.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/scene/parser.h"
#include "raylane/trace/tracer.h"

namespace raylane::testing {

// Rays from random points of the course scene's room (some inside its solids, so back faces
// are met too): three in four in uniform directions, one in four toward a random triangle's
// centroid (the letters are small: uniform directions alone may miss them).
inline std::vector<Rayd> random_rays(const Scene& scene, const Bvh& bvh, int count) {
  Rng rng(5);
  Bounds3f b = bvh.nodes[0].bounds();
  const TriangleTable& tris = scene.table<Triangle>();
  std::vector<Rayd> rays;
  for (int i = 0; i < count; ++i) {
    glm::dvec3 o{};
    for (int k = 0; k < 3; ++k) {
      double u = rng.uniform();
      o[k] = b.lo[k] + (b.hi[k] - b.lo[k]) * u;
    }
    double u1 = rng.uniform(), u2 = rng.uniform();
    glm::dvec3 d = sample_uniform_sphere(u1, u2);
    if (i % 4 == 0 && tris.size() > 0) {
      auto row = uint32_t(std::min<double>(u1 * double(tris.size()), double(tris.size() - 1)));
      glm::dvec3 c =
          (glm::dvec3(tris.p0(row)) + glm::dvec3(tris.p1(row)) + glm::dvec3(tris.p2(row))) / 3.0;
      d = normalize(c - o);
    }
    rays.push_back({o, d});
  }
  // Times of a generator of their own (the rays are what they were), for the moving spheres.
  Rng times(6);
  for (Rayd& r : rays)
    r.time = std::min(times.uniform(), 0x1.fffffffffffffp-1);
  return rays;
}

// Moving spheres in the course scene's room (one standing still), so that every tracer's
// answers cover them at the rays' times.
inline void add_moving_spheres(Scene& scene) {
  MovingSphereTable& t = scene.table<MovingSphere>();
  for (int i = 0; i < 12; ++i) {
    double x = 1 + i % 4 * 3.0, y = 1 + i / 4 * 4.0, z = 1 + i % 3 * 2.5;
    double dx = i % 6 == 0 ? 0 : 2.5, dz = i % 2 ? 1.5 : -1.0;
    t.append(std::array<double, 7>{x, y, z, x + dx, y, z + dz, 0.4 + 0.1 * (i % 3)}, 0);
  }
}

// CSG blocks in the room too (bitten spheres, drilled boxes), so that every tracer's answers
// cover them: their hits name leaves, and their subtracted leaves' normals are turned around.
inline void add_csg_blocks(Scene& scene) {
  for (int i = 0; i < 3; ++i) {
    double x = 2.5 + 3 * i, y = 7, z = 3.5;
    CsgTable draft;
    if (i % 2 == 0)
      draft.add_leaf<Sphere>(std::array<double, 4>{x, y, z, 0.7}, 0);
    else
      draft.add_leaf<Box>(std::array<double, 6>{x - 0.6, y - 0.6, z - 0.6, 1.2, 1.2, 1.2}, 0);
    draft.add_leaf<Cylinder>(std::array<double, 7>{x, y - 1, z + 0.2, 0, 2, 0, 0.3}, 0);
    draft.add_code(kCsgDifference);
    scene.table<Csg>().append_block(draft);
  }
}

// SDF blocks too (tori, spheres melted by a smooth union), in front of the CSG blocks: their
// hits name the leaf nearest the point, their surfaces come from the distance's gradient.
inline void add_sdf_blocks(Scene& scene) {
  SdfTable& t = scene.table<Sdf>();
  for (int i = 0; i < 3; ++i) {
    double x = 2.5 + 3 * i, y = 5.5, z = 3.5;
    t.begin_block();
    if (i % 2 == 0) {
      t.add_torus(std::array<double, 8>{x, y, z, 0, 1, 0.3, 0.5, 0.2}, 0);
    } else {
      t.add_leaf<Sphere>(std::array<double, 4>{x - 0.3, y, z, 0.4}, 0);
      t.add_leaf<Sphere>(std::array<double, 4>{x + 0.3, y, z, 0.4}, 0);
      t.add_code(kSdfSmoothUnion, 0.3f);
    }
    t.end_block();
  }
}

// `check` on the course scene's random rays with every tracer: the packet tracer at every
// instruction set on `count` rays, the double references on `reference_count` of them (slow).
// With moving spheres added (add_moving_spheres); `change` may alter the scene further.
template <class Check, class Change = void (*)(Scene&)>
void with_every_tracer(
    int count, std::size_t reference_count, Check check, Change change = [](Scene&) {}) {
  ParsedScene parsed = load_builtin_scene();
  ASSERT_TRUE(parsed.ok());
  add_moving_spheres(parsed.scene);
  add_csg_blocks(parsed.scene);
  add_sdf_blocks(parsed.scene);
  change(parsed.scene);
  Bvh bvh = build_bvh_and_reorder(parsed.scene);
  const Scene& scene = parsed.scene;
  std::vector<Rayd> rays = random_rays(scene, bvh, count);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(isa_name(isa));
    check(Tracer(scene, bvh, TracerBackend::kPacket, isa), rays);
  }
  rays.resize(reference_count);
  check(Tracer(scene, bvh, TracerBackend::kBvh), rays);
  check(Tracer(scene, bvh, TracerBackend::kScalar), rays);
}

// The hits closest() gives as columns (HitStream) as records, prim and t alone.
inline std::vector<Hit> records_of(const HitStream& columns) {
  std::vector<Hit> hits(columns.t.size());
  for (std::size_t i = 0; i < hits.size(); ++i)
    hits[i].t = columns.t[i], hits[i].prim = PrimRef::from_bits(columns.prim[i]);
  return hits;
}

}  // namespace raylane::testing
