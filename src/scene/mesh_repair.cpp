#include "mesh_repair.h"

#include <climits>
#include <utility>
#include <vector>

namespace raylane::mesh_repair {

void drop_empty_faces(const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    aiMesh& mesh = *scene.mMeshes[m];
    unsigned kept = 0;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices == 0) continue;
      if (kept != f) {  // move the index array down; the source keeps none
        std::swap(mesh.mFaces[kept].mIndices, face.mIndices);
        std::swap(mesh.mFaces[kept].mNumIndices, face.mNumIndices);
      }
      ++kept;
    }
    mesh.mNumFaces = kept;
  }
}

namespace {

// Keeps only the meshes that stay, under their new numbers.
void renumber_node_meshes(aiNode& node, const std::vector<unsigned>& new_index) {
  unsigned kept = 0;
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    unsigned old = node.mMeshes[i];
    if (old < new_index.size() && new_index[old] != UINT_MAX) node.mMeshes[kept++] = new_index[old];
  }
  node.mNumMeshes = kept;
  for (unsigned c = 0; c < node.mNumChildren; ++c)
    if (node.mChildren[c]) renumber_node_meshes(*node.mChildren[c], new_index);
}

}  // namespace

void drop_empty_meshes(const aiScene& scene_as_read) {
  aiScene& scene = const_cast<aiScene&>(scene_as_read);  // owned by the importer; see above
  std::vector<unsigned> new_index(scene.mNumMeshes, UINT_MAX);
  unsigned kept = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    aiMesh* mesh = scene.mMeshes[m];
    if (mesh->mNumFaces == 0 || mesh->mNumVertices == 0) {
      delete mesh;
      continue;
    }
    new_index[m] = kept;
    scene.mMeshes[kept++] = mesh;
  }
  if (kept == scene.mNumMeshes) return;
  scene.mNumMeshes = kept;
  if (scene.mRootNode) renumber_node_meshes(*scene.mRootNode, new_index);
}

bool has_surface(const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
    for (unsigned f = 0; f < scene.mMeshes[m]->mNumFaces; ++f)
      if (scene.mMeshes[m]->mFaces[f].mNumIndices >= 3) return true;
  return false;
}

}  // namespace raylane::mesh_repair
