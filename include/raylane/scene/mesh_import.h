// Mesh files through Assimp: triangulated, smooth normals where missing, placed by
// p → t + s·R·p (normals → R·n, renormalised).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/core/mat3.h"
#include "raylane/prims/triangle.h"
#include "raylane/scene/parse_state.h"

namespace raylane {

struct MeshPlacement {
  Vec3d translation;
  double scale = 1.0;
  Mat3d rotation;
};

struct MeshImportStats {
  uint32_t triangles = 0;           // rows appended
  uint32_t degenerate_dropped = 0;  // zero-area triangles (after placement, in float) skipped
  std::vector<std::string> files;   // every file read: the mesh and what it names (mtllib, ...)
  bool has_uv = false;              // every triangle came with texture coordinates
};

// The scene material for the triangles of one of the file's materials, given the diffuse
// texture that material names: a path (relative ones resolved next to the mesh file), "*N" for
// a texture embedded in the file, or empty for none. Called once per material used, before
// any triangle is appended. Without a chooser, every triangle gets the import's `material`.
using MaterialChooser = std::function<uint32_t(const std::string& texture)>;

inline constexpr uint64_t kMaxMeshTriangles = uint64_t(1) << 28;

// Whether Assimp reads files with this path's extension, other than .scn (our scenes).
bool mesh_extension_known(const std::string& path);

// Imports the mesh file at `path` and appends its triangles to `table` with `material`.
// Nothing is appended on failure.
Result<MeshImportStats> import_mesh_file(const std::string& path, const MeshPlacement& placement,
                                         uint32_t material, TriangleTable& table,
                                         const MaterialChooser& choose = {});
// The same for a file held in memory; the extension of `name` tells the format.
Result<MeshImportStats> import_mesh_memory(const std::string& bytes, const std::string& name,
                                           const MeshPlacement& placement, uint32_t material,
                                           TriangleTable& table);

}  // namespace raylane
