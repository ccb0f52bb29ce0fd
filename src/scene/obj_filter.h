// OBJ faces that name a vertex, texture coordinate or normal outside the file's lists. Assimp's
// OBJ importer refuses the whole file for one such index ("OBJ: vertex index out of range");
// raylane drops those faces instead, as it drops other unusable faces (docs/scene-language.md,
// "Meshes", its paragraph "What is dropped"), and says which lines it dropped.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace raylane {

struct ObjFiltered {
  std::string text;             // the file with each dropped element's line left empty
  std::vector<uint64_t> lines;  // the 1-based lines dropped, in order
};

// The face (`f`), line (`l`) and point (`p`) elements of `obj` whose every index lies in its
// list: a positive index counts from the list's start over the whole file, a negative one back
// from the elements read so far (the OBJ specification, "Referencing groups of vertices").
// An empty `lines` when nothing is dropped (then `text` is left empty too).
ObjFiltered drop_elements_out_of_range(std::string_view obj);

}  // namespace raylane
