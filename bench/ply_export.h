// Writes a triangle table as a binary PLY soup (three vertices per face), so a benchmark mesh
// can be rendered by `raylane render` through a scene file's `mesh` command.
#pragma once

#include <string>

#include "raylane/core/error.h"
#include "raylane/prims/triangle.h"

namespace raylane::bench {

Status write_ply_soup(const std::string& path, const TriangleTable& table);

}  // namespace raylane::bench
