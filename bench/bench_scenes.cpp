#include "bench_scenes.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>

#include "icosphere.h"
#include "raylane/scene/mesh_import.h"
#include "raylane/scene/parser.h"
#include "raylane/trace/ray_set_io.h"

namespace raylane::bench {

namespace {

constexpr uint32_t kWidth = 1024,
                   kHeight = 768;  // docs/benchmarks.md, "Ray sets": 1024×768 primary rays
constexpr const char* kEnginePath =
    "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

Bounds3d scene_bounds(const Scene& s) {
  Bounds3d b;
  PrimKinds::for_each([&](auto kind) {
    const auto& t = s.table<decltype(kind)>();
    for (uint32_t i = 0; i < t.size(); ++i) {
      Bounds3f f = t.bounds(i);
      b.extend(glm::dvec3(f.lo));
      b.extend(glm::dvec3(f.hi));
    }
  });
  return b;
}

// Frames the whole scene from the direction `view` (pointing from the scene to the eye) and
// puts the shadow-ray light above and to the side.
void frame(BenchScene& b, glm::dvec3 view) {
  Bounds3d box = scene_bounds(b.scene);
  glm::dvec3 c = (box.lo + box.hi) * 0.5;
  double radius = length(box.hi - box.lo) * 0.5;
  b.scene.width = kWidth, b.scene.height = kHeight;
  // Close enough that the model fills most of the frame (the bounding sphere overfills it).
  b.scene.camera = look_at(c + normalize(view) * (radius * 1.45), c, 0.5);
  b.light = c + glm::dvec3(0.4, -0.3, 1.5) * radius;
}

ParsedScene parse_text(const std::string& text, const std::string& name) {
  return parse_scene(text, name + ".scn");
}

// Haines's sphereflake (1987, "A Proposal for Standard Graphics Environments"): nine children
// of a third of the radius around each sphere, six on its equator and three above.
void sphereflake(std::ostringstream& out, glm::dvec3 c, double r, glm::dvec3 up, int depth) {
  out << "sphere " << c.x << ' ' << c.y << ' ' << c.z << ' ' << r << '\n';
  if (depth == 0) return;
  glm::dvec3 a = std::abs(up.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  glm::dvec3 u = normalize(cross(up, a)), v = cross(up, u);
  for (int k = 0; k < 9; ++k) {
    double phi = (k < 6 ? k / 6.0 : (k - 6) / 3.0 + 1 / 12.0) * 2 * M_PI;
    double lat = k < 6 ? 0.0 : M_PI / 4;
    glm::dvec3 dir =
        normalize((u * std::cos(phi) + v * std::sin(phi)) * std::cos(lat) + up * std::sin(lat));
    sphereflake(out, c + dir * (r * 4 / 3), r / 3, dir, depth - 1);
  }
}

std::optional<BenchScene> make_sphereflake() {
  std::ostringstream out;
  out << "camera 0 0 0 1\nbrdf 0.7 0.7 0.7 0 0 0 1\n";
  sphereflake(out, {0, 0, 0}, 1.0, {0, 0, 1}, 5);
  ParsedScene p = parse_text(out.str(), "sphereflake");
  if (!p.ok()) return std::nullopt;
  BenchScene b{"sphereflake", std::move(p.scene), {}, {}, 0};
  frame(b, {1.0, -1.6, 0.9});
  return b;
}

// A cubic lattice: a box at each of 16³ nodes, a cylinder along each edge between them.
std::optional<BenchScene> make_lattice() {
  constexpr int n = 16;
  std::ostringstream out;
  out << "camera 0 0 0 1\nbrdf 0.7 0.7 0.7 0 0 0 1\n";
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        out << "box " << i - 0.15 << ' ' << j - 0.15 << ' ' << k - 0.15 << " 0.3 0.3 0.3\n";
        if (i + 1 < n) out << "cylinder " << i << ' ' << j << ' ' << k << " 1 0 0 0.06\n";
        if (j + 1 < n) out << "cylinder " << i << ' ' << j << ' ' << k << " 0 1 0 0.06\n";
        if (k + 1 < n) out << "cylinder " << i << ' ' << j << ' ' << k << " 0 0 1 0.06\n";
      }
  ParsedScene p = parse_text(out.str(), "lattice");
  if (!p.ok()) return std::nullopt;
  BenchScene b{"lattice", std::move(p.scene), {}, {}, 0};
  frame(b, {1.0, -1.4, 0.8});
  return b;
}

std::optional<BenchScene> make_engine(std::string* why) {
  BenchScene b;
  b.name = "engine";
  b.scene.materials.push_back(Material::default_grey());
  auto r = import_mesh_file(kEnginePath, MeshPlacement{}, 0, b.scene.table<Triangle>());
  if (!r.ok()) {
    if (why) *why = "needs Debian's assimp-testmodels: " + r.error();
    return std::nullopt;
  }
  frame(b, {1.0, -1.3, 0.7});
  return b;
}

std::string& bunny_path_setting() {
  static std::string path;
  return path;
}

// The Stanford bunny of npm's `bunny` package, written as PLY by tools/make_bunny.
std::optional<BenchScene> make_bunny(std::string* why) {
  BenchScene b;
  b.name = "bunny";
  b.scene.materials.push_back(Material::default_grey());
  std::string path = bunny_path();
  auto r = import_mesh_file(path, MeshPlacement{}, 0, b.scene.table<Triangle>());
  if (!r.ok()) {
    if (why) *why = "run tools/make_bunny first, or name the file with --bunny (" + r.error() + ")";
    return std::nullopt;
  }
  frame(b, {0.3, -1.0, 0.4});
  return b;
}

std::optional<BenchScene> make_testscene() {
  ParsedScene p = load_builtin_scene();
  if (!p.ok()) return std::nullopt;
  BenchScene b{"testscene", std::move(p.scene), {}, {}, 0};
  b.scene.width = kWidth, b.scene.height = kHeight;
  // Shadow rays aim at the first light sphere's centre and stop at its surface.
  for (PrimRef l : b.scene.lights)
    if (l.tag() == tag_of<Sphere>) {
      b.light = glm::dvec3(b.scene.table<Sphere>().center(l.row()));
      b.light_gap = b.scene.table<Sphere>().r[l.row()] * 1.01;
      break;
    }
  return b;
}

// A CSG lens — the intersection of two unit spheres 0.8 apart on z, a rim of radius 0.6 — seen
// along z, and the plain sphere of radius 0.6 that fills the same pixels: the measure
// of what a block's sweep costs over its leaves' own tests (docs/scene-language.md, "CSG
// blocks"). Shadow rays aim at a point beside the camera.
std::optional<BenchScene> make_lens_or_sphere(bool lens) {
  const std::string solid =
      lens ? "csg\nsphere 0 0 0.8 1\nsphere 0 0 -0.8 1\nintersect\nend\n" : "sphere 0 0 0 0.6\n";
  ParsedScene p = parse_scene("camera 0 0 2.2 0.3\nbrdf 0.5 0.5 0.5 0 0 0 1\n" + solid,
                              lens ? "csglens.scn" : "lenssphere.scn");
  if (!p.ok()) return std::nullopt;
  BenchScene b{lens ? "csglens" : "lenssphere", std::move(p.scene), {}, {}, 0};
  b.scene.width = kWidth, b.scene.height = kHeight;
  b.light = {1.0, 1.0, 3.0};
  return b;
}

// A torus (an sdf block, R 0.45, r 0.15, its axis tilted 30° toward the camera) and the plain
// sphere of radius R + r that fills its outline: what the float march costs over an analytic
// test (its target: at least a fifth of the sphere's rays/s; docs/scene-language.md, "SDF blocks").
std::optional<BenchScene> make_torus_or_sphere(bool torus) {
  const std::string solid =
      torus ? "sdf\ntorus 0 0 0 0 0.5 0.866 0.45 0.15\nend\n" : "sphere 0 0 0 0.6\n";
  ParsedScene p = parse_scene("camera 0 0 2.2 0.3\nbrdf 0.5 0.5 0.5 0 0 0 1\n" + solid,
                              torus ? "sdftorus.scn" : "torussphere.scn");
  if (!p.ok()) return std::nullopt;
  BenchScene b{torus ? "sdftorus" : "torussphere", std::move(p.scene), {}, {}, 0};
  b.scene.width = kWidth, b.scene.height = kHeight;
  b.light = {1.0, 1.0, 3.0};
  return b;
}

std::optional<BenchScene> make_icosphere() {
  BenchScene b;
  b.name = "icosphere";
  b.scene.materials.push_back(Material::default_grey());
  add_displaced_icosphere(b.scene.table<Triangle>(), 8, 0);
  frame(b, {1.0, -1.5, 0.6});
  return b;
}

// A user's mesh (bench_trace --mesh): a .tris soup in its file order, or any mesh file Assimp
// reads, as `raylane trace` loads them, so the rays of a user's .rays set meet the same
// triangles. Shadow rays are not made for it (its sets are the user's).
std::optional<BenchScene> make_user_mesh(const std::string& path, std::string* why) {
  BenchScene b;
  b.name = std::filesystem::path(path).stem().string();
  b.scene.materials.push_back(Material::default_grey());
  TriangleTable& t = b.scene.table<Triangle>();
  Status read = ok_status();
  if (std::filesystem::path(path).extension() == ".tris") {
    auto n = read_triangle_soup(path, 0, t);
    if (!n) read = Error{n.error()};
  } else {
    auto n = import_mesh_file(path, MeshPlacement{}, 0, t);
    if (!n) read = Error{n.error()};
  }
  if (!read) {
    if (why) *why = read.error();
    return std::nullopt;
  }
  return b;
}

}  // namespace

std::string bunny_path() {
  if (!bunny_path_setting().empty()) return bunny_path_setting();
  // The program's own build tree, not a path compiled in: a binary copied or built elsewhere
  // (another worktree, a build-foo folder) reads the bunny of the tree it sits in.
  std::error_code ec;
  std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return "bench-data/bunny.ply";
  return (exe.parent_path().parent_path() / "bench-data" / "bunny.ply").string();
}

void set_bunny_path(std::string path) {
  bunny_path_setting() = std::move(path);
}

std::vector<std::string> bench_scene_names() {
  return {"testscene", "bunny",   "engine",     "icosphere", "sphereflake",
          "lattice",   "csglens", "lenssphere", "sdftorus",  "torussphere"};
}

CameraSpec look_at(const glm::dvec3& eye, const glm::dvec3& target, double ry) {
  glm::dvec3 forward = normalize(target - eye);
  glm::dvec3 right = normalize(cross(forward, glm::dvec3(0, 0, 1)));
  glm::dvec3 up = cross(right, forward);
  CameraSpec c;
  c.eye = eye;
  c.ry = ry;
  // Columns: R·x = right, R·y = up, R·(−z) = forward.
  for (int i = 0; i < 3; ++i) {
    c.rotation[0][i] = right[i];
    c.rotation[1][i] = up[i];
    c.rotation[2][i] = -forward[i];
  }
  return c;
}

const BenchScene* bench_scene(const std::string& name, std::string* why) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<BenchScene>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  if (auto it = cache.find(name); it != cache.end()) return it->second.get();
  std::optional<BenchScene> b;
  if (name == "testscene") b = make_testscene();
  if (name == "bunny") b = make_bunny(why);
  if (name == "engine") b = make_engine(why);
  if (name == "icosphere") b = make_icosphere();
  if (name == "sphereflake") b = make_sphereflake();
  if (name == "lattice") b = make_lattice();
  if (name == "csglens" || name == "lenssphere") b = make_lens_or_sphere(name == "csglens");
  if (name == "sdftorus" || name == "torussphere") b = make_torus_or_sphere(name == "sdftorus");
  if (name.rfind(kUserMeshPrefix, 0) == 0)
    b = make_user_mesh(name.substr(kUserMeshPrefix.size()), why);
  if (!b) {
    if (why && why->empty()) *why = "no such scene or it failed to build: " + name;
    return nullptr;
  }
  b->bvh = build_bvh_and_reorder(b->scene, BvhConfig{.wide_nodes = true});
  // The wide nodes are collapsed from the binary tree after it is built, so without them the
  // tree is the one render_bvh_config builds (and the scene's rows are in its order).
  if (!render_bvh_config(b->scene).wide_nodes) {
    b->packets_only = b->bvh;
    b->packets_only.wide = WideBvh{};
  }
  auto& slot = cache[name];
  slot = std::make_unique<BenchScene>(std::move(*b));
  return slot.get();
}

}  // namespace raylane::bench
