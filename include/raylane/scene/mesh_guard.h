// Checks made before a mesh file reaches Assimp, for inputs Assimp does not survive.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "raylane/core/error.h"

namespace raylane {

inline constexpr uint64_t kMaxMeshFileBytes = uint64_t(4) << 30;

// The checks made before a mesh file is read: its size, and for a PLY file (scene/ply.h, which
// reads every PLY itself) a header that follows the grammar and declares no more elements than
// the file can hold. `head` is the start of the file (at least its header, if it has one).
// Other formats pass; Assimp reads them.
Status check_mesh_plausible(std::string_view head, uint64_t file_size, const std::string& name);

}  // namespace raylane
