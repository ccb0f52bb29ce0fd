// Mesh files through Assimp: triangulated, smooth normals where missing, placed by
// p → t + s·R·p (normals → R·n, renormalised).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/core/rotation.h"
#include "raylane/image/image.h"
#include "raylane/prims/triangle.h"
#include "raylane/scene/parse_state.h"

namespace raylane {

struct MeshPlacement {
  glm::dvec3 translation{};
  double scale = 1.0;
  glm::dmat3 rotation{1.0};
};

struct MeshImportStats {
  uint32_t triangles = 0;           // rows appended
  uint32_t degenerate_dropped = 0;  // zero-area triangles (after placement, in float) skipped
  std::vector<std::string> files;   // every file read: the mesh and what it names (mtllib, ...)
  bool has_uv = false;              // every triangle came with texture coordinates
  // An OBJ file's lines whose faces named an element outside its lists, dropped (1-based).
  std::vector<uint64_t> obj_lines_dropped;
};

// The diffuse texture one of a mesh file's materials names.
struct MeshTexture {
  // A file: its path, relative ones resolved next to the mesh file. Embedded in the mesh file
  // (glTF binary, FBX…): "MESH [embedded *N]", a name for messages and for reading it once.
  // Empty: the material names none.
  std::string name;
  bool embedded = false;
  // Embedded as an image file (PNG, JPEG…): its bytes, inside the importer's scene, and the
  // extension the mesh file gives it (TGA has no magic number).
  std::string_view file_bytes;
  std::string extension;
  // Embedded as raw 8-bit texels: already converted to linear RGB (sRGB-decoded).
  const Image* texels = nullptr;

  static MeshTexture file(std::string path) {
    MeshTexture t;
    t.name = std::move(path);
    return t;
  }
};

// The scene material for the triangles of one of the file's materials, given the diffuse
// texture that material names. Called once per material used, before any triangle is
// appended. Without a chooser, every triangle gets the import's `material`.
using MaterialChooser = std::function<uint32_t(const MeshTexture& texture)>;

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
