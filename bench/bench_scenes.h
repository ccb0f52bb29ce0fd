// The benchmark scenes (docs/benchmarks.md, "Scenes"): made by raylane's own code at bench time, so
// nothing large is committed and nothing is downloaded except through the package manager.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "raylane/bvh/bvh.h"
#include "raylane/scene/scene.h"

namespace raylane::bench {

struct BenchScene {
  std::string name;
  Scene scene;
  Bvh bvh;               // always with the 8-wide nodes, for the single-ray and hybrid tracers
  glm::dvec3 light{};    // the point shadow rays aim at
  double light_gap = 0;  // shadow rays stop this far short of it (a light sphere's radius)
  // The BVH `raylane render` traces this scene with (render_bvh_config): `bvh` itself when
  // that has wide nodes, else the same binary tree without them (packets alone).
  Bvh packets_only{};
  const Bvh& rendered() const { return packets_only.empty() ? bvh : packets_only; }
};

// testscene (the course's, built in), bunny (the Stanford bunny of npm's `bunny` package,
// 3,674 triangles, written by tools/make_bunny), engine (2CylinderEngine.glb of Debian's
// assimp-testmodels, ~110k triangles), icosphere (a displaced icosphere of 1.31M triangles),
// sphereflake (66k spheres), lattice (4096 boxes joined by 11520 cylinders), csglens (a CSG
// block: two sphere leaves intersected) and lenssphere (the sphere filling the lens's pixels),
// sdftorus (an sdf block: a tilted torus) and torussphere (the sphere filling its outline).
std::vector<std::string> bench_scene_names();

// The bunny's PLY file: bench-data/bunny.ply in the build tree this program was built in (its
// folder's parent, where tools/make_bunny writes by default), unless set (bench_trace --bunny).
std::string bunny_path();
void set_bunny_path(std::string path);

// Builds the scene (and its BVH), or says why it cannot (e.g. a package is not installed).
// Cached: the same object is returned for the same name. A name kUserMeshPrefix + PATH is a
// user's mesh file (bench_trace --mesh): a .tris soup or any mesh file Assimp reads.
inline constexpr std::string_view kUserMeshPrefix = "mesh:";
const BenchScene* bench_scene(const std::string& name, std::string* why = nullptr);

// A camera at `eye` looking at `target`, z up, vertical half-angle tangent `ry`.
CameraSpec look_at(const glm::dvec3& eye, const glm::dvec3& target, double ry);

}  // namespace raylane::bench
