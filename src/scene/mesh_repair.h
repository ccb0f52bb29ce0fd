// What raylane mends in a scene Assimp has read before Assimp's own post-processing runs on it
// (mesh_import.cpp): faces without indices and meshes without faces, which Assimp's steps do not
// survive. The importer owns the scene; it is edited in place between reading and
// post-processing, which Assimp's API allows.
#pragma once

#include <assimp/scene.h>

namespace raylane::mesh_repair {

// Drops faces without indices: Debian's Assimp 5.2.5 is built with its assertions on, and its
// triangulation step aborts the process on such a face (found by fuzz_mesh: a binary PLY whose
// face list count reads 0).
void drop_empty_faces(const aiScene& scene);

// Deletes the meshes that hold no face or no vertex and renumbers the nodes' mesh indices:
// Assimp's validation step fails a whole file on one empty mesh (an STL with an empty `solid`
// beside a real one), though the others are fine.
void drop_empty_meshes(const aiScene& scene);

// Whether any mesh of a scene as read has a face of three or more corners (a surface).
bool has_surface(const aiScene& scene);

}  // namespace raylane::mesh_repair
