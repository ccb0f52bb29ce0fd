// A PLY file's triangles into the triangle table (src/scene/mesh_append.h).
#include <bit>
#include <cmath>
#include <new>

#include "mesh_append.h"
#include "raylane/core/strings.h"

namespace raylane {

namespace {

// For each vertex, the first vertex at exactly the same position (−0 and +0 alike), so that
// files which repeat a corner for each face — triangle soups, as STL converters and raylane's
// benchmark export write — still get smooth normals, as Assimp's welding gave them. An
// open-addressing table of vertex indices, sized to twice the vertices. Each distinct position
// gets a compact id (0, 1, … in order of first appearance), so that what is kept per position
// — the normal sums — is sized to the distinct positions, a third of a soup's vertices.
struct Welded {
  std::vector<uint32_t> id;  // per vertex: its position's id
  uint32_t positions = 0;    // distinct positions
};

Welded weld_positions(const std::vector<glm::vec3>& p) {
  auto key = [&](uint32_t i) {
    return std::array<float, 3>{p[i].x + 0.0f, p[i].y + 0.0f, p[i].z + 0.0f};
  };
  auto hash = [&](uint32_t i) {
    auto k = key(i);
    uint64_t h = 0;
    for (float f : k)
      h = (h ^ std::bit_cast<uint32_t>(f)) * 0x9E3779B97F4A7C15ull;  // Fibonacci hashing
    return h ^ (h >> 29);
  };
  std::size_t size = 16;
  while (size < 2 * p.size())
    size *= 2;
  constexpr uint32_t kEmpty = UINT32_MAX;
  std::vector<uint32_t> slots(size, kEmpty);
  Welded w;
  w.id.resize(p.size());
  for (uint32_t i = 0; i < p.size(); ++i) {
    std::size_t s = hash(i) & (size - 1);
    while (slots[s] != kEmpty && key(slots[s]) != key(i))
      s = (s + 1) & (size - 1);
    if (slots[s] == kEmpty) slots[s] = i, w.id[i] = w.positions++;
    w.id[i] = w.id[slots[s]];
  }
  return w;
}

// Vertex normals for a file that has none: each corner adds its face's unit normal weighted by
// the corner's angle (Thürmer and Wüthrich, "Computing vertex normals from polygonal facets",
// JGT 3(1), 1998), so the result does not depend on how a polygon was cut into triangles.
// Vertices at the same position share their normal: the result is one normal per position
// id of `welded`.
std::vector<glm::vec3> angle_weighted_normals(const PlyMesh& mesh, const Welded& welded) {
  const std::vector<uint32_t>& first = welded.id;
  std::vector<glm::dvec3> sum(welded.positions);
  for (const auto& t : mesh.triangles) {
    std::array<glm::dvec3, 3> p = {glm::dvec3(mesh.positions[t[0]]),
                                   glm::dvec3(mesh.positions[t[1]]),
                                   glm::dvec3(mesh.positions[t[2]])};
    glm::dvec3 n = cross(p[1] - p[0], p[2] - p[0]);
    double len = length(n);
    if (!(len > 0)) continue;
    n = n / len;
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
      double angle = std::atan2(length(cross(a, b)), dot(a, b));
      sum[first[t[k]]] = sum[first[t[k]]] + angle * n;
    }
  }
  std::vector<glm::vec3> out(sum.size());
  for (std::size_t i = 0; i < sum.size(); ++i) {
    double len = length(sum[i]);
    out[i] =
        len > 0 ? glm::vec3(sum[i] / len) : glm::vec3();  // zero: append_placed uses the face's
  }
  return out;
}

Result<MeshImportStats> append_ply(const PlyMesh& mesh, const std::string& name,
                                   const MeshPlacement& placement, uint32_t material,
                                   TriangleTable& table) {
  if (mesh.triangles.empty())
    return Error{cat("mesh ", quote_path(name), " has no faces (points or lines only, or empty)")};
  if (mesh.triangles.size() > kMaxMeshTriangles ||
      table.size() + mesh.triangles.size() > PrimRef::kMaxRows)
    return Error{
        cat("mesh ", quote_path(name), " has too many triangles (", mesh.triangles.size(), ")")};
  // Made normals are per position id; a file's own, per vertex.
  const bool make = mesh.normals.empty();
  Welded welded = make ? weld_positions(mesh.positions) : Welded{};
  const std::vector<glm::vec3> made =
      make ? angle_weighted_normals(mesh, welded) : std::vector<glm::vec3>();
  auto normal = [&](uint32_t v) { return make ? made[welded.id[v]] : mesh.normals[v]; };
  MeshImportStats stats;
  stats.has_uv = !mesh.uvs.empty();
  table_reserve(table, table.size() + mesh.triangles.size());
  if (stats.has_uv && !table.has_uv()) table.add_uv_columns();
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    if (Status s = check_placed(placement, glm::dvec3(mesh.positions[i]), i, name); !s)
      return Error{s.error()};
  for (const auto& t : mesh.triangles) {
    std::array<glm::dvec3, 3> p{}, n{};
    std::array<TexCoord, 3> uv{};
    for (int k = 0; k < 3; ++k) {
      p[k] = glm::dvec3(mesh.positions[t[k]]);
      n[k] = glm::dvec3(normal(t[k]));
      if (stats.has_uv) uv[k] = mesh.uvs[t[k]];
    }
    append_placed(p, n, uv, placement, material, table, stats);
  }
  if (stats.triangles == 0)
    return Error{cat("mesh ", quote_path(name), " has only zero-area triangles (",
                     stats.degenerate_dropped, ")")};
  return stats;
}

// `bytes` may lie in `owned`, which is freed once the file is read: the table then grows
// without the file's bytes beside it (scale runs of bench/README.md: peak memory).
Result<MeshImportStats> read_and_append(std::string_view bytes, std::string& owned,
                                        const std::string& name, const MeshPlacement& placement,
                                        uint32_t material, TriangleTable& table,
                                        const MaterialChooser& choose) {
  try {
    auto mesh = read_ply(bytes, name);
    std::string().swap(owned);
    if (!mesh) return Error{mesh.error()};
    uint32_t mat = material;
    if (choose && !mesh->texture_files.empty())
      mat = choose(MeshTexture::file(texture_next_to(mesh->texture_files.front(), name)));
    return append_ply(*mesh, name, placement, mat, table);
  } catch (const std::bad_alloc&) {
    return Error{cat("out of memory reading mesh ", quote_path(name))};
  }
}

}  // namespace

Result<MeshImportStats> import_ply(std::string_view bytes, const std::string& name,
                                   const MeshPlacement& placement, uint32_t material,
                                   TriangleTable& table, const MaterialChooser& choose) {
  std::string none;
  return read_and_append(bytes, none, name, placement, material, table, choose);
}

Result<MeshImportStats> import_ply(std::string&& owned, const std::string& name,
                                   const MeshPlacement& placement, uint32_t material,
                                   TriangleTable& table, const MaterialChooser& choose) {
  std::string_view bytes = owned;
  return read_and_append(bytes, owned, name, placement, material, table, choose);
}

}  // namespace raylane
