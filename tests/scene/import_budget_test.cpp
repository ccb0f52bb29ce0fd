// Imports are bounded by what the file holds (docs/scene-language.md, "Error classes"): files of a
// few hundred bytes whose headers announce 10^8 elements made Assimp allocate gigabytes before
// reading them. Within raylane's allocation budget (256 MiB plus 64 bytes per byte read) they are
// an error that names the file, and real files still load (the corpus test). PLY files never reach
// Assimp: raylane's reader checks a list's length against the bytes left before reading it.
#include <gtest/gtest.h>

#include <cstring>

#include "raylane/core/alloc_budget.h"
#include "raylane/scene/mesh_import.h"

namespace raylane {
namespace {

std::string binary_ply_with_face_list(uint32_t announced) {
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uint int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  s.append(reinterpret_cast<const char*>(v), sizeof v);
  s.append(reinterpret_cast<const char*>(&announced), 4);
  const int32_t idx[3] = {0, 1, 2};
  s.append(reinterpret_cast<const char*>(idx), sizeof idx);
  return s;
}

struct Hostile {
  const char* name;
  std::string bytes;
  const char* refusal = "would take more than";  // what the error must say
};

TEST(ImportBudget, AnnouncedSizesBeyondTheFileAreErrors) {
  const Hostile cases[] = {
      {"list.ply", binary_ply_with_face_list(150000000),
       "byte 204: expected a list length the file can hold, found 150000000"},
      {"many.off", "OFF\n100000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"many.x",
       "xof 0303txt 0032\nMesh m {\n100000000;\n0;0;0;,\n1;0;0;,\n0;1;0;;\n1;\n3;0,1,2;;\n}\n"},
  };
  for (const Hostile& h : cases) {
    SCOPED_TRACE(h.name);
    TriangleTable table;
    auto r = import_mesh_memory(h.bytes, h.name, MeshPlacement{}, 0, table);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().find(h.name), std::string::npos) << r.error();
    bool budget = std::strcmp(h.refusal, "would take more than") == 0;
    if ((AllocBudget::enforced() || !budget) && r.error().find(h.refusal) == std::string::npos)
      ADD_FAILURE() << "refused for another reason: " << r.error();
    EXPECT_EQ(table.size(), 0u);
  }
  // The same PLY announcing what it holds loads: the budget is not what refused the others.
  TriangleTable table;
  auto ok = import_mesh_memory(binary_ply_with_face_list(3), "list.ply", MeshPlacement{}, 0, table);
  ASSERT_TRUE(ok) << ok.error();
  EXPECT_EQ(table.size(), 1u);
}

}  // namespace
}  // namespace raylane
