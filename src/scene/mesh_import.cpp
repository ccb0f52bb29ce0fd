#include "raylane/scene/mesh_import.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <filesystem>
#include <fstream>
#include <new>
#include <utility>

#include "raylane/core/strings.h"
#include "raylane/scene/mesh_guard.h"

namespace raylane {

namespace {

constexpr unsigned kImportFlags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_GenSmoothNormals | aiProcess_PreTransformVertices |
                                  aiProcess_SortByPType | aiProcess_ValidateDataStructure;

void configure(Assimp::Importer& importer) {
  // Points and lines are not surfaces: drop them rather than fail.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
}

// Drops faces without indices before post-processing: Debian's Assimp 5.2.5 is built with its
// assertions on, and its triangulation step aborts the process on such a face (found by
// fuzz_mesh: a binary PLY whose face list count reads 0). The importer owns the scene; it is
// edited in place between reading and post-processing, which Assimp's API allows.
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

// Reads without post-processing, removes what Assimp's own steps do not survive, then runs
// the steps. Returns null with the importer's error string set on failure.
const aiScene* read_checked(Assimp::Importer& importer, const aiScene* raw) {
  if (!raw) return nullptr;
  drop_empty_faces(*raw);
  return importer.ApplyPostProcessing(kImportFlags);
}

Vec3d to_vec(const aiVector3D& v) {
  return {double(v.x), double(v.y), double(v.z)};
}

uint64_t count_triangles(const aiScene& scene) {
  uint64_t n = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
    n += scene.mMeshes[m]->mNumFaces;
  return n;
}

// Appends the placed triangles of one mesh; faces that are not triangles are skipped.
void append_mesh(const aiMesh& mesh, const MeshPlacement& pl, uint32_t material,
                 TriangleTable& table, MeshImportStats& stats) {
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;
    std::array<Vec3f, 3> p, n;
    bool bad_index = false;
    for (int k = 0; k < 3; ++k) {
      unsigned i = face.mIndices[k];
      if (i >= mesh.mNumVertices) {
        bad_index = true;
        break;
      }
      p[k] = Vec3f(pl.translation + pl.scale * (pl.rotation * to_vec(mesh.mVertices[i])));
      Vec3d nk = mesh.mNormals ? pl.rotation * to_vec(mesh.mNormals[i]) : Vec3d();
      double len = length(nk);
      n[k] = len > 0 && std::isfinite(len) ? Vec3f(nk / len) : Vec3f();
    }
    if (bad_index) continue;
    Vec3d ng = cross(Vec3d(p[1]) - Vec3d(p[0]), Vec3d(p[2]) - Vec3d(p[0]));
    if (length_squared(ng) == 0.0) {
      ++stats.degenerate_dropped;
      continue;
    }
    // A vertex without a usable normal takes the face normal.
    for (auto& nk : n)
      if (nk == Vec3f()) nk = Vec3f(normalize(ng));
    table.append(p, n, material);
    ++stats.triangles;
  }
}

Result<MeshImportStats> convert(const aiScene* scene, Assimp::Importer& importer,
                                const std::string& name, const MeshPlacement& placement,
                                uint32_t material, TriangleTable& table) {
  if (!scene)
    return Error{cat("cannot read mesh ", in_quotes(name), ": ", importer.GetErrorString())};
  uint64_t total = count_triangles(*scene);
  if (total == 0) return Error{cat("mesh ", in_quotes(name), " has no triangles")};
  if (total > kMaxMeshTriangles || table.size() + total > PrimRef::kMaxRows)
    return Error{cat("mesh ", in_quotes(name), " has too many triangles (", total, ")")};
  MeshImportStats stats;
  table_reserve(table, table.size() + total);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
    append_mesh(*scene->mMeshes[m], placement, material, table, stats);
  if (stats.triangles == 0)
    return Error{cat("mesh ", in_quotes(name), " has only zero-area triangles")};
  return stats;
}

// The first bytes of a file: enough for any PLY header the guard needs to read.
std::string read_head(const std::string& path) {
  constexpr std::size_t kHeadBytes = 1 << 16;
  std::string head(kHeadBytes, '\0');
  std::ifstream in(path, std::ios::binary);
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(std::size_t(in.gcount()));
  return head;
}

}  // namespace

Result<MeshImportStats> import_mesh_file(const std::string& path, const MeshPlacement& placement,
                                         uint32_t material, TriangleTable& table) {
  try {
    std::error_code ec;
    uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) return Error{cat("cannot read mesh ", in_quotes(path), ": ", ec.message())};
    if (Status s = check_mesh_plausible(read_head(path), size, path); !s) return Error{s.error()};
    Assimp::Importer importer;
    configure(importer);
    const aiScene* scene = read_checked(importer, importer.ReadFile(path, 0));
    return convert(scene, importer, path, placement, material, table);
  } catch (const std::bad_alloc&) {
    return Error{cat("out of memory reading mesh ", in_quotes(path))};
  } catch (const std::exception& e) {
    return Error{cat("cannot read mesh ", in_quotes(path), ": ", e.what())};
  }
}

Result<MeshImportStats> import_mesh_memory(const std::string& bytes, const std::string& name,
                                           const MeshPlacement& placement, uint32_t material,
                                           TriangleTable& table) {
  try {
    if (Status s = check_mesh_plausible(bytes, bytes.size(), name); !s) return Error{s.error()};
    Assimp::Importer importer;
    configure(importer);
    std::string hint = std::filesystem::path(name).extension().string();
    if (!hint.empty()) hint.erase(0, 1);
    const aiScene* scene = read_checked(
        importer, importer.ReadFileFromMemory(bytes.data(), bytes.size(), 0, hint.c_str()));
    return convert(scene, importer, name, placement, material, table);
  } catch (const std::bad_alloc&) {
    return Error{cat("out of memory reading mesh ", in_quotes(name))};
  } catch (const std::exception& e) {
    return Error{cat("cannot read mesh ", in_quotes(name), ": ", e.what())};
  }
}

}  // namespace raylane
