// Checks made before a mesh file reaches Assimp, for inputs Assimp does not survive.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "raylane/core/error.h"

namespace raylane {

inline constexpr uint64_t kMaxMeshFileBytes = uint64_t(4) << 30;

// A PLY header declares element counts; Assimp 5.2's PLY reader loops for hours on a header
// that declares far more elements than the file holds (found by a test: `element vertex
// 99999999999` and no data). Every property of every element takes at least one byte, so a
// file whose declared elements need more bytes than it has is rejected here. `head` is the
// start of the file (at least its header, if it has one). A file named .ply or starting with
// "ply" in any case must have a header that follows the PLY grammar exactly; other formats
// pass.
Status check_mesh_plausible(std::string_view head, uint64_t file_size, const std::string& name);

}  // namespace raylane
