// What the two mesh readers (Assimp's, and raylane's own PLY reader) share: placing a file's
// triangle in the scene and appending it, and resolving a texture a file names.
#pragma once

#include <array>
#include <string>

#include "raylane/scene/mesh_import.h"
#include "raylane/scene/ply.h"

namespace raylane {

// One triangle in the file's frame, placed by p → t + s·R·p and n → R·n (renormalised; a
// normal that is zero or not finite becomes the face normal). A triangle of zero area after
// placement, in float, is counted in stats.degenerate_dropped and not appended.
void append_placed(const std::array<glm::dvec3, 3>& p, const std::array<glm::dvec3, 3>& n,
                   const std::array<TexCoord, 3>& uv, const MeshPlacement& placement,
                   uint32_t material, TriangleTable& table, MeshImportStats& stats);

// Where a file's vertex lands, in float as the table stores it: t + s·R·p.
glm::vec3 placed_position(const MeshPlacement& placement, const glm::dvec3& p);
// An error naming the vertex (its index in the file, `index`) if its placed position is not
// finite in float; the mesh line's translation, scale or orientation took it beyond float.
Status check_placed(const MeshPlacement& placement, const glm::dvec3& p, uint64_t index,
                    const std::string& mesh_name);

// A texture file named inside a mesh file, resolved next to it; "*N" (embedded) and "" stay.
// Files written on Windows name textures with backslashes (".\wood.jpg"), and many name them
// by their author's absolute path: the first of (the name as written, with '/' for each
// backslash, its last component alone) that is a file next to the mesh file is taken; if
// none is, the name with '/'.
std::string texture_next_to(const std::string& file, const std::string& mesh_path);

// The triangles of a PLY file (scene/ply.h) held in `bytes`, read without Assimp. Smooth
// normals are made where the file has none; `choose` gets the texture a `comment TextureFile`
// line names, if any.
Result<MeshImportStats> import_ply(std::string_view bytes, const std::string& name,
                                   const MeshPlacement& placement, uint32_t material,
                                   TriangleTable& table, const MaterialChooser& choose);
// The same, freeing the file's bytes once they are read.
Result<MeshImportStats> import_ply(std::string&& bytes, const std::string& name,
                                   const MeshPlacement& placement, uint32_t material,
                                   TriangleTable& table, const MaterialChooser& choose);

}  // namespace raylane
