#include "raylane/scene/mesh_import.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <new>
#include <utility>

#include "mesh_append.h"
#include "mesh_repair.h"
#include "obj_filter.h"
#include "raylane/core/alloc_budget.h"
#include "raylane/core/input_file.h"
#include "raylane/core/limits.h"
#include "raylane/core/strings.h"
#include "raylane/image/input_image.h"
#include "raylane/scene/mesh_guard.h"
#include "raylane/scene/ply.h"

namespace raylane {

namespace {

// What Assimp may allocate while it reads a mesh: a fixed allowance plus a multiple of the
// bytes of the files it reads (the mesh and what it names). Real files stay far below (the
// 1.31M-triangle binary PLY of the benchmark peaks near 32 bytes per byte); a header that
// announces more than its file holds hits the limit before its arrays are filled.
constexpr uint64_t kImportAllowance = uint64_t(256) << 20;
constexpr uint64_t kImportBytesPerFileByte = 64;

constexpr unsigned kImportFlags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_GenSmoothNormals | aiProcess_PreTransformVertices |
                                  aiProcess_SortByPType | aiProcess_ValidateDataStructure;

void configure(Assimp::Importer& importer) {
  // Points and lines are not surfaces: drop them rather than fail.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
}

// The first vertex that is not finite, as "mesh M vertex V (x y z)"; empty if none. Assimp
// reads inf and NaN coordinates as given; a triangle made of them has no place in a BVH.
std::string first_nonfinite_vertex(const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        return cat("mesh ", m, " vertex ", v, " (", p.x, " ", p.y, " ", p.z, ")");
    }
  }
  return "";
}

// Reads without post-processing, removes what Assimp's own steps do not survive, then runs
// the steps. Returns null with the importer's error string set on failure; `faceless` is set
// when the file holds no surface at all (points or lines only, or nothing).
const aiScene* read_checked(Assimp::Importer& importer, const aiScene* raw, bool& faceless) {
  if (!raw) return nullptr;
  faceless = !mesh_repair::has_surface(*raw);
  if (faceless) return nullptr;
  mesh_repair::drop_empty_faces(*raw);
  mesh_repair::drop_empty_meshes(*raw);
  return importer.ApplyPostProcessing(kImportFlags);
}

// Assimp opens the mesh and every file it names (an OBJ's mtllib, a glTF's buffers, images)
// through this. A path that is not a regular file is refused — a FIFO would block fopen for
// ever, a device never ends — and so is any mode but reading. Every file opened is recorded.
class GuardedIOSystem final : public Assimp::DefaultIOSystem {
 public:
  void set_budget(AllocBudget* budget) { budget_ = budget; }

  bool Exists(const char* file) const override { return regular_file_size(file).ok(); }

  Assimp::IOStream* Open(const char* file, const char* mode = "rb") override {
    std::string_view m = mode ? mode : "rb";
    if (m.find_first_of("wa+") != std::string_view::npos) {
      refused_.push_back(cat(file, ": raylane opens mesh files for reading only"));
      return nullptr;
    }
    auto size = regular_file_size(file);
    if (!size) {
      refused_.push_back(cat(file, ": ", size.error()));
      return nullptr;
    }
    // Assimp opens a file more than once (to detect its format, then to read it): each file
    // is recorded, and adds to the budget, once.
    const bool first_time = std::find(opened_.begin(), opened_.end(), file) == opened_.end();
    if (first_time) {
      opened_.emplace_back(file);
      if (budget_) budget_->grow(kImportBytesPerFileByte * *size);
    }
    if (is_obj(file))
      if (Assimp::IOStream* kept = open_obj_without_bad_elements(file, first_time)) return kept;
    return DefaultIOSystem::Open(file, mode);
  }

  static bool is_obj(const char* file) {
    std::string ext = std::filesystem::path(file).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".obj";
  }

  // The lines of an OBJ file whose elements were dropped (obj_filter.h).
  const std::vector<uint64_t>& obj_lines_dropped() const { return obj_lines_dropped_; }

  const std::vector<std::string>& opened() const { return opened_; }
  // "; a.mtl: not a regular file (a FIFO)" for each refusal, to append to Assimp's message.
  std::string refusals() const {
    std::string out;
    for (const std::string& r : refused_)
      out += "; " + r;
    return out;
  }

 private:
  // The OBJ file as Assimp should read it: without the faces that name an element outside its
  // lists, which would make Assimp refuse the whole file. Nothing when none are dropped (or the
  // file cannot be read: Assimp's own open says why).
  Assimp::IOStream* open_obj_without_bad_elements(const char* file, bool first_time) {
    auto bytes = read_input_file(file, kMaxMeshFileBytes, "the mesh");
    if (!bytes) return nullptr;
    ObjFiltered kept = drop_elements_out_of_range(*bytes);
    if (kept.lines.empty()) return nullptr;
    if (first_time) obj_lines_dropped_ = kept.lines;
    texts_.push_back(std::move(kept.text));
    const std::string& text = texts_.back();
    return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(text.data()), text.size());
  }

  std::vector<std::string> opened_, refused_;
  std::deque<std::string> texts_;  // the filtered OBJ texts, alive while the importer reads
  std::vector<uint64_t> obj_lines_dropped_;
  AllocBudget* budget_ = nullptr;
};

// Runs read() (Assimp's ReadFile or ReadFileFromMemory) and its post-processing within an
// AllocBudget of kImportAllowance plus kImportBytesPerFileByte per byte of `bytes` and of every
// file `io` opens. Assimp may turn the std::bad_alloc of an exceeded budget into its own error
// or let it through; either way the budget says what happened.
template <class Read>
Result<const aiScene*> read_within_budget(Assimp::Importer& importer, const std::string& name,
                                          uint64_t bytes, GuardedIOSystem* io, Read read) {
  AllocBudget budget(kImportAllowance + kImportBytesPerFileByte * bytes);
  if (io) io->set_budget(&budget);
  const aiScene* scene = nullptr;
  bool out_of_memory = false, faceless = false;
  try {
    scene = read_checked(importer, read(), faceless);
  } catch (const std::bad_alloc&) {
    out_of_memory = true;
  } catch (const std::exception& e) {
    if (io) io->set_budget(nullptr);
    return Error{cat("cannot read mesh ", quote_path(name), ": ", e.what())};
  }
  if (io) io->set_budget(nullptr);
  if (budget.exceeded())
    return Error{cat("mesh ", quote_path(name), ": reading it would take more than ",
                     budget.limit() >> 20, " MiB (", kImportAllowance >> 20, " MiB and ",
                     kImportBytesPerFileByte,
                     " bytes per byte of the files it reads): it "
                     "announces more data than it holds")};
  if (out_of_memory) return Error{cat("out of memory reading mesh ", quote_path(name))};
  if (faceless)
    return Error{cat("mesh ", quote_path(name), " has no faces (points or lines only, or empty)")};
  if (!scene) {
    std::string ext = std::filesystem::path(name).extension().string();
    std::string tried = ext.empty() ? "by its contents" : "as " + ext;
    return Error{cat("cannot read mesh ", quote_path(name), " (Assimp read it ", tried,
                     "): ", escape_invisible(importer.GetErrorString()))};
  }
  return scene;
}

glm::dvec3 to_vec(const aiVector3D& v) {
  return {double(v.x), double(v.y), double(v.z)};
}

uint64_t count_triangles(const aiScene& scene) {
  uint64_t n = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
    n += scene.mMeshes[m]->mNumFaces;
  return n;
}

// An embedded texture stored as raw texels (aiTexture with mHeight > 0: BGRA, 8 bits each,
// sRGB-encoded like every 8-bit image), as linear RGB; alpha is dropped as for image files.
Image embedded_texels(const aiTexture& t) {
  Image img(t.mWidth, t.mHeight);
  for (uint32_t y = 0; y < t.mHeight; ++y)
    for (uint32_t x = 0; x < t.mWidth; ++x) {
      const aiTexel& c = t.pcData[std::size_t(y) * t.mWidth + x];
      img.set(x, y,
              {float(srgb_to_linear(c.r / 255.0)), float(srgb_to_linear(c.g / 255.0)),
               float(srgb_to_linear(c.b / 255.0))});
    }
  return img;
}

// The scene material for one of the file's materials: its diffuse texture (glTF's base colour
// where that is how Assimp reports it) handed to `choose`, embedded or resolved next to the
// mesh file. Assimp names an embedded texture "*N", or (glTF binary, FBX) by the file name it
// had, which GetEmbeddedTexture also matches.
uint32_t choose_material(const aiScene& scene, const aiMaterial& m, const std::string& mesh_path,
                         const MaterialChooser& choose) {
  aiString name;
  if (m.GetTexture(aiTextureType_DIFFUSE, 0, &name) != AI_SUCCESS &&
      m.GetTexture(aiTextureType_BASE_COLOR, 0, &name) != AI_SUCCESS)
    return choose(MeshTexture{});
  auto [embedded, index] = scene.GetEmbeddedTextureAndIndex(name.C_Str());
  if (embedded == nullptr)
    return choose(MeshTexture::file(texture_next_to(name.C_Str(), mesh_path)));
  MeshTexture t;
  t.name = cat(mesh_path, " [embedded *", index, "]");
  t.embedded = true;
  const bool compressed = embedded->mHeight == 0;
  if (compressed) {
    t.file_bytes = {reinterpret_cast<const char*>(embedded->pcData), embedded->mWidth};
    t.extension = embedded->achFormatHint;
    return choose(t);
  }
  if (uint64_t(embedded->mWidth) * embedded->mHeight > kMaxImagePixels) return choose(t);
  Image texels = embedded_texels(*embedded);
  t.texels = &texels;
  return choose(t);
}

// The scene material of each of the file's materials that a mesh uses.
std::vector<uint32_t> choose_materials(const aiScene& scene, const std::string& mesh_path,
                                       uint32_t material, const MaterialChooser& choose) {
  std::vector<uint32_t> out(scene.mNumMaterials, material);
  if (!choose) return out;
  std::vector<bool> used(scene.mNumMaterials, false);
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
    if (scene.mMeshes[m]->mMaterialIndex < scene.mNumMaterials)
      used[scene.mMeshes[m]->mMaterialIndex] = true;
  for (unsigned k = 0; k < scene.mNumMaterials; ++k)
    if (used[k]) out[k] = choose_material(scene, *scene.mMaterials[k], mesh_path, choose);
  return out;
}

bool has_uvs(const aiMesh& mesh) {
  return mesh.mTextureCoords[0] != nullptr && mesh.mNumUVComponents[0] >= 2;
}

// Appends the placed triangles of one mesh; faces that are not triangles are skipped.
void append_mesh(const aiMesh& mesh, const MeshPlacement& pl, uint32_t material,
                 TriangleTable& table, MeshImportStats& stats) {
  const bool uv = has_uvs(mesh);
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;
    std::array<glm::dvec3, 3> p{}, n{};
    std::array<TexCoord, 3> t{};
    bool bad_index = false;
    for (int k = 0; k < 3; ++k) {
      unsigned i = face.mIndices[k];
      if (i >= mesh.mNumVertices) {
        bad_index = true;
        break;
      }
      p[k] = to_vec(mesh.mVertices[i]);
      n[k] = mesh.mNormals ? to_vec(mesh.mNormals[i]) : glm::dvec3();
      if (uv) {
        const aiVector3D& c = mesh.mTextureCoords[0][i];
        t[k] = {std::isfinite(c.x) ? c.x : 0.0, std::isfinite(c.y) ? c.y : 0.0};
      }
    }
    if (!bad_index) append_placed(p, n, t, pl, material, table, stats);
  }
}

Result<MeshImportStats> convert(const aiScene* scene, const std::string& name,
                                const MeshPlacement& placement, uint32_t material,
                                TriangleTable& table, const MaterialChooser& choose) {
  if (std::string bad = first_nonfinite_vertex(*scene); !bad.empty())
    return Error{
        cat("mesh ", quote_path(name), ": expected finite vertex coordinates, found ", bad)};
  uint64_t total = count_triangles(*scene);
  if (total == 0)
    return Error{cat("mesh ", quote_path(name), " has no faces (points or lines only, or empty)")};
  if (total > kMaxMeshTriangles || table.size() + total > PrimRef::kMaxRows)
    return Error{cat("mesh ", quote_path(name), " has too many triangles (", total, ")")};
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      if (Status s = check_placed(placement, glm::dvec3(p.x, p.y, p.z), v, name); !s)
        return Error{m == 0 ? s.error() : cat(s.error(), " (in its mesh ", m, ")")};
    }
  }
  MeshImportStats stats;
  stats.has_uv = true;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
    stats.has_uv = stats.has_uv && has_uvs(*scene->mMeshes[m]);
  std::vector<uint32_t> materials = choose_materials(*scene, name, material, choose);
  table_reserve(table, table.size() + total);
  // UV columns appear with the first mesh that has UVs; the scene drops them again at its end
  // if no textured material uses them (Scene::resolve_textures).
  if (stats.has_uv && !table.has_uv()) table.add_uv_columns();
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    uint32_t mat =
        mesh.mMaterialIndex < materials.size() ? materials[mesh.mMaterialIndex] : material;
    append_mesh(mesh, placement, mat, table, stats);
  }
  if (stats.triangles == 0)
    return Error{cat("mesh ", quote_path(name), " has only zero-area triangles (",
                     stats.degenerate_dropped, ")")};
  return stats;
}

// The first bytes of a file: 64 KiB, or for a PLY file whose header is longer (long comment
// blocks), its whole header up to kMaxPlyHeaderBytes, which the guard reads.
std::string read_head(const std::string& path, uint64_t file_size) {
  constexpr uint64_t kHeadBytes = 1 << 16;
  auto head = read_input_head(path, kHeadBytes, "the mesh");
  if (!head) return {};
  if (head->size() < file_size && is_ply(*head, path) &&
      head->find("\nend_header") == std::string::npos) {
    auto longer = read_input_head(path, kMaxPlyHeaderBytes, "the mesh");
    if (longer) return std::move(*longer);
  }
  return std::move(*head);
}

// convert(), with running out of memory for the table an error rather than an exception.
Result<MeshImportStats> convert_or_fail(const aiScene* scene, const std::string& name,
                                        const MeshPlacement& placement, uint32_t material,
                                        TriangleTable& table, const MaterialChooser& choose = {}) {
  try {
    return convert(scene, name, placement, material, table, choose);
  } catch (const std::bad_alloc&) {
    return Error{cat("out of memory storing the triangles of mesh ", quote_path(name))};
  }
}

}  // namespace

bool mesh_extension_known(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  // .scn is a scene of ours, though Assimp also claims it (Caligari trueSpace).
  return !ext.empty() && ext != ".scn" && Assimp::Importer().IsExtensionSupported(ext.c_str());
}

Result<MeshImportStats> import_mesh_file(const std::string& path, const MeshPlacement& placement,
                                         uint32_t material, TriangleTable& table,
                                         const MaterialChooser& choose) {
  auto size = regular_file_size(path);
  if (!size) return Error{cat("cannot read mesh ", quote_path(path), ": ", size.error())};
  std::string head = read_head(path, *size);
  if (Status s = check_mesh_plausible(head, *size, path); !s) return Error{s.error()};
  if (is_ply(head, path)) {
    auto bytes = read_input_file(path, kMaxMeshFileBytes, "the mesh");
    if (!bytes) return Error{bytes.error()};
    auto stats = import_ply(std::move(*bytes), path, placement, material, table, choose);
    if (stats) stats->files = {path};
    return stats;
  }
  Assimp::Importer importer;
  configure(importer);
  auto* io = new GuardedIOSystem;  // the importer owns and deletes it
  importer.SetIOHandler(io);
  auto scene =
      read_within_budget(importer, path, 0, io, [&] { return importer.ReadFile(path, 0); });
  if (!scene) return Error{scene.error() + io->refusals()};
  auto stats = convert_or_fail(*scene, path, placement, material, table, choose);
  if (!stats) return Error{stats.error()};
  stats->files = io->opened();
  stats->obj_lines_dropped = io->obj_lines_dropped();
  return stats;
}

Result<MeshImportStats> import_mesh_memory(const std::string& bytes, const std::string& name,
                                           const MeshPlacement& placement, uint32_t material,
                                           TriangleTable& table) {
  if (Status s = check_mesh_plausible(bytes, bytes.size(), name); !s) return Error{s.error()};
  if (is_ply(bytes, name)) return import_ply(bytes, name, placement, material, table, {});
  Assimp::Importer importer;
  configure(importer);
  std::string hint = std::filesystem::path(name).extension().string();
  if (!hint.empty()) hint.erase(0, 1);
  ObjFiltered kept;
  if (GuardedIOSystem::is_obj(name.c_str())) kept = drop_elements_out_of_range(bytes);
  const std::string& read = kept.lines.empty() ? bytes : kept.text;
  auto scene = read_within_budget(importer, name, read.size(), nullptr, [&] {
    return importer.ReadFileFromMemory(read.data(), read.size(), 0, hint.c_str());
  });
  if (!scene) return Error{scene.error()};
  auto stats = convert_or_fail(*scene, name, placement, material, table);
  if (stats) stats->obj_lines_dropped = std::move(kept.lines);
  return stats;
}

}  // namespace raylane

// --- shared with the PLY reader (mesh_append.h) ---

namespace raylane {

glm::vec3 placed_position(const MeshPlacement& pl, const glm::dvec3& p) {
  return glm::vec3(pl.translation + pl.scale * (pl.rotation * p));
}

namespace {
// "(x y z)" with 9 significant digits, for messages.
std::string point_text(const glm::dvec3& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.9g %.9g %.9g)", p.x, p.y, p.z);
  return text;
}
}  // namespace

Status check_placed(const MeshPlacement& pl, const glm::dvec3& p, uint64_t index,
                    const std::string& mesh_name) {
  glm::vec3 q = placed_position(pl, p);
  if (std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z)) return ok_status();
  glm::dvec3 exact = pl.translation + pl.scale * (pl.rotation * p);
  return Error{cat("mesh ", quote_path(mesh_name), ": vertex ", index, " ", point_text(p),
                   " is placed at ", point_text(exact),
                   ", beyond float (the largest is about 3.4e38); expected a translation and "
                   "scale that keep the mesh within float")};
}

void append_placed(const std::array<glm::dvec3, 3>& p_file, const std::array<glm::dvec3, 3>& n_file,
                   const std::array<TexCoord, 3>& uv, const MeshPlacement& pl, uint32_t material,
                   TriangleTable& table, MeshImportStats& stats) {
  std::array<glm::vec3, 3> p{}, n{};
  for (int k = 0; k < 3; ++k) {
    p[k] = placed_position(pl, p_file[k]);
    glm::dvec3 nk = pl.rotation * n_file[k];
    double len = length(nk);
    n[k] = len > 0 && std::isfinite(len) ? glm::vec3(nk / len) : glm::vec3();
  }
  glm::dvec3 ng = cross(glm::dvec3(p[1]) - glm::dvec3(p[0]), glm::dvec3(p[2]) - glm::dvec3(p[0]));
  if (length_squared(ng) == 0.0) {
    ++stats.degenerate_dropped;
    return;
  }
  // A vertex without a usable normal takes the face normal.
  for (auto& nk : n)
    if (nk == glm::vec3()) nk = glm::vec3(normalize(ng));
  table.append(p, n, material, &uv);
  ++stats.triangles;
}

namespace {

std::string next_to(const std::string& file, const std::string& mesh_path) {
  std::filesystem::path p(file);
  if (p.is_relative()) p = std::filesystem::path(mesh_path).parent_path() / p;
  return p.lexically_normal().string();
}

bool is_file(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

}  // namespace

std::string texture_next_to(const std::string& file, const std::string& mesh_path) {
  if (file.empty() || file[0] == '*') return file;  // embedded: "*N"
  std::string as_written = next_to(file, mesh_path);
  if (is_file(as_written)) return as_written;
  std::string slashed = file;
  std::replace(slashed.begin(), slashed.end(), '\\', '/');
  std::string with_slashes = next_to(slashed, mesh_path);
  if (is_file(with_slashes)) return with_slashes;
  std::string bare = next_to(std::filesystem::path(slashed).filename().string(), mesh_path);
  return is_file(bare) ? bare : with_slashes;
}

}  // namespace raylane
