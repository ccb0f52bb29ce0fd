#include "support/random_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace raylane::testing {

namespace {

Vec3d uniform_in_cube(std::mt19937_64& rng, double extent, Vec3d offset) {
  std::uniform_real_distribution<double> u(-extent, extent);
  return offset + Vec3d(u(rng), u(rng), u(rng));
}

Vec3d unit_vector(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Vec3d v;
  do
    v = {g(rng), g(rng), g(rng)};
  while (length_squared(v) < 1e-12);
  return normalize(v);
}

}  // namespace

Scene random_scene(uint32_t seed, int n, double extent, double size, Vec3d offset) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> s(0.2 * size, size);
  Scene scene;
  scene.materials.push_back(Material{});
  Material light;
  light.is_light = true;
  light.emission = {1, 1, 1};
  scene.materials.push_back(light);
  for (int i = 0; i < n; ++i) {
    Vec3d c = uniform_in_cube(rng, extent, offset);
    uint32_t mat = i % 7 == 0 ? 1 : 0;
    std::array<double, 4> sp{c.x, c.y, c.z, s(rng)};
    scene.table<Sphere>().append(sp, mat);
    if (mat == 1)
      scene.lights.push_back(PrimRef(tag_of<Sphere>, uint32_t(scene.table<Sphere>().size() - 1)));
    c = uniform_in_cube(rng, extent, offset);
    std::array<double, 6> bx{c.x, c.y, c.z, s(rng), -s(rng), s(rng)};
    scene.table<Box>().append(bx, 0);
    c = uniform_in_cube(rng, extent, offset);
    Vec3d a = unit_vector(rng) * (2 * s(rng));
    std::array<double, 7> cy{c.x, c.y, c.z, a.x, a.y, a.z, 0.3 * s(rng)};
    scene.table<Cylinder>().append(cy, 0);
    c = uniform_in_cube(rng, extent, offset);
    std::array<Vec3f, 3> p, nn;
    for (int k = 0; k < 3; ++k)
      p[k] = Vec3f(c + unit_vector(rng) * s(rng));
    Vec3f ng(normalize(cross(Vec3d(p[1]) - Vec3d(p[0]), Vec3d(p[2]) - Vec3d(p[0]))));
    nn = {ng, ng, ng};
    scene.table<Triangle>().append(p, nn, 0);
  }
  // Moving spheres from a generator of their own, so the other kinds are what they were: each
  // moves up to 4 sizes (one in five not at all), a few emit.
  std::mt19937_64 moving(seed ^ 0x6d6f76696e67ull);
  for (int i = 0; i < n; ++i) {
    Vec3d c0 = uniform_in_cube(moving, extent, offset);
    Vec3d c1 = i % 5 == 0 ? c0 : c0 + unit_vector(moving) * (4 * s(moving));
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

void add_closed_uv_sphere(Scene& scene, uint32_t seed, int rings, int segments, Vec3d offset) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(1.0, 1.3);
  using std::numbers::pi;
  // Vertices: north pole, (rings − 1) rings of `segments`, south pole; computed once and
  // shared, so neighbouring triangles see bit-identical vertices.
  std::vector<Vec3f> v;
  v.push_back(Vec3f(offset + Vec3d(0, 0, jitter(rng))));
  for (int i = 1; i < rings; ++i) {
    double theta = pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      double phi = 2 * pi * j / segments;
      Vec3d d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      v.push_back(Vec3f(offset + d * jitter(rng)));
    }
  }
  v.push_back(Vec3f(offset + Vec3d(0, 0, -jitter(rng))));
  const int south = int(v.size()) - 1;
  auto at = [&](int ring, int seg) { return 1 + (ring - 1) * segments + (seg % segments); };
  auto tri = [&](int a, int b, int c) {
    Vec3d ng = normalize(cross(Vec3d(v[b]) - Vec3d(v[a]), Vec3d(v[c]) - Vec3d(v[a])));
    Vec3f n(ng);
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

std::vector<Rayd> random_rays(uint32_t seed, int n, double extent, Vec3d offset) {
  std::mt19937_64 rng(seed);
  std::vector<Rayd> rays;
  rays.reserve(n);
  for (int i = 0; i < n; ++i) {
    Vec3d o = uniform_in_cube(rng, extent, offset);
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
