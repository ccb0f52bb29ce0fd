#include "support/random_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace raylane::testing {

namespace {

glm::dvec3 uniform_in_cube(std::mt19937_64& rng, double extent, glm::dvec3 offset) {
  std::uniform_real_distribution<double> u(-extent, extent);
  return offset + glm::dvec3(u(rng), u(rng), u(rng));
}

glm::dvec3 unit_vector(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  glm::dvec3 v{};
  do
    v = {g(rng), g(rng), g(rng)};
  while (length_squared(v) < 1e-12);
  return normalize(v);
}

}  // namespace

Scene random_scene(uint32_t seed, int n, double extent, double size, glm::dvec3 offset) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> s(0.2 * size, size);
  Scene scene;
  scene.materials.push_back(Material{});
  Material light;
  light.is_light = true;
  light.emission = {1, 1, 1};
  scene.materials.push_back(light);
  for (int i = 0; i < n; ++i) {
    glm::dvec3 c = uniform_in_cube(rng, extent, offset);
    uint32_t mat = i % 7 == 0 ? 1 : 0;
    std::array<double, 4> sp{c.x, c.y, c.z, s(rng)};
    scene.table<Sphere>().append(sp, mat);
    if (mat == 1)
      scene.lights.push_back(PrimRef(tag_of<Sphere>, uint32_t(scene.table<Sphere>().size() - 1)));
    c = uniform_in_cube(rng, extent, offset);
    std::array<double, 6> bx{c.x, c.y, c.z, s(rng), -s(rng), s(rng)};
    scene.table<Box>().append(bx, 0);
    c = uniform_in_cube(rng, extent, offset);
    glm::dvec3 a = unit_vector(rng) * (2 * s(rng));
    std::array<double, 7> cy{c.x, c.y, c.z, a.x, a.y, a.z, 0.3 * s(rng)};
    scene.table<Cylinder>().append(cy, 0);
    c = uniform_in_cube(rng, extent, offset);
    std::array<glm::vec3, 3> p{}, nn{};
    for (int k = 0; k < 3; ++k)
      p[k] = glm::vec3(c + unit_vector(rng) * s(rng));
    glm::vec3 ng(
        normalize(cross(glm::dvec3(p[1]) - glm::dvec3(p[0]), glm::dvec3(p[2]) - glm::dvec3(p[0]))));
    nn = {ng, ng, ng};
    scene.table<Triangle>().append(p, nn, 0);
  }
  // Moving spheres from a generator of their own, so the other kinds are what they were: each
  // moves up to 4 sizes (one in five not at all), a few emit.
  std::mt19937_64 moving(seed ^ 0x6d6f76696e67ull);
  for (int i = 0; i < n; ++i) {
    glm::dvec3 c0 = uniform_in_cube(moving, extent, offset);
    glm::dvec3 c1 = i % 5 == 0 ? c0 : c0 + unit_vector(moving) * (4 * s(moving));
    uint32_t mat = i % 11 == 0 ? 1 : 0;
    std::array<double, 7> mb{c0.x, c0.y, c0.z, c1.x, c1.y, c1.z, s(moving)};
    scene.table<MovingSphere>().append(mb, mat);
    if (mat == 1)
      scene.lights.push_back(
          PrimRef(tag_of<MovingSphere>, uint32_t(scene.table<MovingSphere>().size() - 1)));
  }
  scene.camera = CameraSpec{};
  return scene;
}

void add_closed_uv_sphere(Scene& scene, uint32_t seed, int rings, int segments, glm::dvec3 offset) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(1.0, 1.3);
  using std::numbers::pi;
  // Vertices: north pole, (rings − 1) rings of `segments`, south pole; computed once and
  // shared, so neighbouring triangles see bit-identical vertices.
  std::vector<glm::vec3> v;
  v.push_back(glm::vec3(offset + glm::dvec3(0, 0, jitter(rng))));
  for (int i = 1; i < rings; ++i) {
    double theta = pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      double phi = 2 * pi * j / segments;
      glm::dvec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta));
      v.push_back(glm::vec3(offset + d * jitter(rng)));
    }
  }
  v.push_back(glm::vec3(offset + glm::dvec3(0, 0, -jitter(rng))));
  const int south = int(v.size()) - 1;
  auto at = [&](int ring, int seg) { return 1 + (ring - 1) * segments + (seg % segments); };
  auto tri = [&](int a, int b, int c) {
    glm::dvec3 ng =
        normalize(cross(glm::dvec3(v[b]) - glm::dvec3(v[a]), glm::dvec3(v[c]) - glm::dvec3(v[a])));
    glm::vec3 n(ng);
    scene.table<Triangle>().append({v[a], v[b], v[c]}, {n, n, n}, 0);
  };
  if (scene.materials.empty()) scene.materials.push_back(Material{});
  for (int j = 0; j < segments; ++j) {
    tri(0, at(1, j), at(1, j + 1));
    for (int i = 1; i < rings - 1; ++i) {
      tri(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      tri(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
    tri(at(rings - 1, j), south, at(rings - 1, j + 1));
  }
}

std::vector<Rayd> random_rays(uint32_t seed, int n, double extent, glm::dvec3 offset) {
  std::mt19937_64 rng(seed);
  std::vector<Rayd> rays;
  rays.reserve(n);
  for (int i = 0; i < n; ++i) {
    glm::dvec3 o = uniform_in_cube(rng, extent, offset);
    rays.push_back({o, unit_vector(rng)});
  }
  // Times of their own generator (the rays are what they were): the shutter's ends, its middle
  // and random times, for the moving spheres.
  std::mt19937_64 times(seed ^ 0x74696d65ull);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::size_t i = 0; i < rays.size(); ++i)
    rays[i].time = i % 4 == 0 ? 0.0 : i % 4 == 1 ? 0.5 : double(std::min(u(times), 0x1.fffffep-1f));
  return rays;
}

Rayd round_to_float(const Rayd& r) {
  return ray_cast<double>(ray_cast<float>(r));
}

}  // namespace raylane::testing
