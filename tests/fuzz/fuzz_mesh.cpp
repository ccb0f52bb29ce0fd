// libFuzzer target: a mesh file's bytes → triangles through Assimp, or an error. The first
// byte picks the format hint (PLY or OBJ); the project's PLY guard stays in the path because
// import_mesh_memory calls it first.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "raylane/scene/mesh_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const char* name = (data[0] & 1) ? "fuzz.obj" : "fuzz.ply";
  std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  raylane::TriangleTable table;
  raylane::MeshPlacement placement{{0, 0, 0}, 1.0, glm::dmat3(1.0)};
  auto stats = raylane::import_mesh_memory(bytes, name, placement, 0, table);
  // Nothing is appended on failure; on success, exactly the triangles reported.
  if (!stats ? table.size() != 0 : table.size() != stats->triangles) std::abort();
  return 0;
}
