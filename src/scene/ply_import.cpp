// A PLY file's triangles into the triangle table (src/scene/mesh_append.h).
#include <cmath>
#include <new>

#include "mesh_append.h"
#include "raylane/core/strings.h"

namespace raylane {

namespace {

// Vertex normals for a file that has none: each corner adds its face's unit normal weighted by
// the corner's angle (Thürmer and Wüthrich, "Computing vertex normals from polygonal facets",
// JGT 3(1), 1998), so the result does not depend on how a polygon was cut into triangles.
// Vertices are shared by index, as PLY files share them.
std::vector<Vec3f> angle_weighted_normals(const PlyMesh& mesh) {
  std::vector<Vec3d> sum(mesh.positions.size());
  for (const auto& t : mesh.triangles) {
    std::array<Vec3d, 3> p = {Vec3d(mesh.positions[t[0]]), Vec3d(mesh.positions[t[1]]),
                              Vec3d(mesh.positions[t[2]])};
    Vec3d n = cross(p[1] - p[0], p[2] - p[0]);
    double len = length(n);
    if (!(len > 0)) continue;
    n = n / len;
    for (int k = 0; k < 3; ++k) {
      Vec3d a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
      double angle = std::atan2(length(cross(a, b)), dot(a, b));
      sum[t[k]] = sum[t[k]] + angle * n;
    }
  }
  std::vector<Vec3f> out(sum.size());
  for (std::size_t i = 0; i < sum.size(); ++i) {
    double len = length(sum[i]);
    out[i] = len > 0 ? Vec3f(sum[i] / len) : Vec3f();  // zero: append_placed uses the face's
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
  const std::vector<Vec3f> made =
      mesh.normals.empty() ? angle_weighted_normals(mesh) : std::vector<Vec3f>();
  const std::vector<Vec3f>& normals = mesh.normals.empty() ? made : mesh.normals;
  MeshImportStats stats;
  stats.has_uv = !mesh.uvs.empty();
  table_reserve(table, table.size() + mesh.triangles.size());
  if (stats.has_uv && !table.has_uv()) table.add_uv_columns();
  for (const auto& t : mesh.triangles) {
    std::array<Vec3d, 3> p, n;
    std::array<TexCoord, 3> uv{};
    for (int k = 0; k < 3; ++k) {
      p[k] = Vec3d(mesh.positions[t[k]]);
      n[k] = Vec3d(normals[t[k]]);
      if (stats.has_uv) uv[k] = mesh.uvs[t[k]];
    }
    append_placed(p, n, uv, placement, material, table, stats);
  }
  if (stats.triangles == 0)
    return Error{cat("mesh ", quote_path(name), " has only zero-area triangles (",
                     stats.degenerate_dropped, ")")};
  return stats;
}

}  // namespace

Result<MeshImportStats> import_ply(std::string_view bytes, const std::string& name,
                                   const MeshPlacement& placement, uint32_t material,
                                   TriangleTable& table, const MaterialChooser& choose) {
  try {
    auto mesh = read_ply(bytes, name);
    if (!mesh) return Error{mesh.error()};
    uint32_t mat = material;
    if (choose && !mesh->texture_files.empty())
      mat = choose(texture_next_to(mesh->texture_files.front(), name));
    return append_ply(*mesh, name, placement, mat, table);
  } catch (const std::bad_alloc&) {
    return Error{cat("out of memory reading mesh ", quote_path(name))};
  }
}

}  // namespace raylane
