#include "icosphere.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace raylane::bench {

namespace {

using Tri = std::array<uint32_t, 3>;

struct Mesh {
  std::vector<glm::dvec3> v;
  std::vector<Tri> f;
};

Mesh icosahedron() {
  const double g = (1 + std::sqrt(5.0)) / 2;
  Mesh m;
  for (double a : {-1.0, 1.0})
    for (double b : {-g, g}) {
      m.v.push_back(normalize(glm::dvec3(0, a, b)));
      m.v.push_back(normalize(glm::dvec3(a, b, 0)));
      m.v.push_back(normalize(glm::dvec3(b, 0, a)));
    }
  // Faces: every triple of mutually nearest neighbours, wound outward.
  double e0 = 1e9;
  for (uint32_t j = 1; j < 12; ++j)
    e0 = std::min(e0, length(m.v[0] - m.v[j]));
  auto near = [&](uint32_t i, uint32_t j) { return length(m.v[i] - m.v[j]) < e0 * 1.01; };
  for (uint32_t i = 0; i < 12; ++i)
    for (uint32_t j = i + 1; j < 12; ++j)
      for (uint32_t k = j + 1; k < 12; ++k)
        if (near(i, j) && near(j, k) && near(i, k)) {
          Tri t{i, j, k};
          if (dot(cross(m.v[j] - m.v[i], m.v[k] - m.v[i]), m.v[i]) < 0) std::swap(t[1], t[2]);
          m.f.push_back(t);
        }
  return m;
}

// Splits every triangle into four; midpoints are shared through an edge → vertex map.
void subdivide(Mesh& m) {
  std::unordered_map<uint64_t, uint32_t> mid;
  mid.reserve(m.f.size() * 2);
  auto midpoint = [&](uint32_t a, uint32_t b) {
    uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
    auto [it, fresh] = mid.try_emplace(key, uint32_t(m.v.size()));
    if (fresh) m.v.push_back(normalize(m.v[a] + m.v[b]));
    return it->second;
  };
  std::vector<Tri> out;
  out.reserve(m.f.size() * 4);
  for (const Tri& t : m.f) {
    uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
    out.push_back({t[0], ab, ca});
    out.push_back({ab, t[1], bc});
    out.push_back({ca, bc, t[2]});
    out.push_back({ab, bc, ca});
  }
  m.f.swap(out);
}

// Smooth bumps of a few wavelengths: enough relief that rays graze and shadow each other.
double displacement(const glm::dvec3& p) {
  return 1 + 0.06 * std::sin(9 * p.x) * std::sin(7 * p.y) * std::sin(8 * p.z) +
         0.02 * std::sin(31 * p.x + 17 * p.z) * std::cos(23 * p.y);
}

// The points of face (a, b, c)'s grid, row i (weight i/k toward b) after row: point (i, j) has
// weights ((k − i − j), i, j)/k toward (a, b, c). The corners are summed in the order of their
// vertex indices, so a point on an edge comes out the same from both faces that share it (a
// crack would let rays through the closed mesh).
std::vector<glm::dvec3> face_grid(const Mesh& m, const Tri& f, int k) {
  std::vector<glm::dvec3> grid;
  grid.reserve(std::size_t(k + 1) * (k + 2) / 2);
  for (int i = 0; i <= k; ++i)
    for (int j = 0; j <= k - i; ++j) {
      std::array<std::pair<uint32_t, int>, 3> w = {{{f[0], k - i - j}, {f[1], i}, {f[2], j}}};
      std::sort(w.begin(), w.end());
      glm::dvec3 p(0, 0, 0);
      for (auto [v, weight] : w)
        p = p + m.v[v] * (double(weight) / k);
      grid.push_back(normalize(p));
    }
  return grid;
}

void append_displaced(TriangleTable& table, const std::array<glm::dvec3, 3>& dir,
                      uint32_t material) {
  std::array<glm::vec3, 3> p{}, n{};
  for (int k = 0; k < 3; ++k)
    p[k] = glm::vec3(dir[k] * displacement(dir[k])), n[k] = glm::vec3(dir[k]);
  table.append(p, n, material);
}

}  // namespace

void add_displaced_geodesic_sphere(TriangleTable& table, int frequency, uint32_t material) {
  const Mesh m = icosahedron();
  const int k = std::max(frequency, 1);
  table_reserve(table, table.size() + std::size_t(20) * k * k);
  for (const Tri& f : m.f) {
    std::vector<glm::dvec3> grid = face_grid(m, f, k);
    // Row i starts at i·(k + 1) − i(i − 1)/2 (row i holds k + 1 − i points).
    auto at = [&](int i, int j) { return grid[std::size_t(i * (k + 1) - i * (i - 1) / 2 + j)]; };
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k - i; ++j) {
        // Both keep the face's outward winding: (a, b, c) maps to (i, j), (i + 1, j), (i, j + 1).
        append_displaced(table, {at(i, j), at(i + 1, j), at(i, j + 1)}, material);
        if (i + j + 1 < k)
          append_displaced(table, {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}, material);
      }
  }
}

void add_displaced_icosphere(TriangleTable& table, int levels, uint32_t material) {
  Mesh m = icosahedron();
  for (int l = 0; l < levels; ++l)
    subdivide(m);
  std::vector<glm::vec3> p(m.v.size()), n(m.v.size());
  for (std::size_t i = 0; i < m.v.size(); ++i) {
    p[i] = glm::vec3(m.v[i] * displacement(m.v[i]));
    n[i] = glm::vec3(m.v[i]);
  }
  table_reserve(table, table.size() + m.f.size());
  for (const Tri& t : m.f)
    table.append({p[t[0]], p[t[1]], p[t[2]]}, {n[t[0]], n[t[1]], n[t[2]]}, material);
}

}  // namespace raylane::bench
