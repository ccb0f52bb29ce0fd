// What a `mesh` line brought in, for `raylane info`: its file, the line, the triangles kept
// and dropped, and their bounds as placed (so a camera can be aimed at it).
#pragma once

#include <cstdint>
#include <string>

#include "raylane/core/bounds3.h"
#include "raylane/core/error.h"

namespace raylane {

struct MeshSummary {
  std::string file;
  FileLoc loc;
  uint32_t triangles = 0, degenerate_dropped = 0;
  uint32_t material = 0;  // the `mesh` line's material
  bool has_uv = false;    // every triangle has texture coordinates
  Bounds3f bounds;
};

}  // namespace raylane
