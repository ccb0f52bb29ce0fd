// The `texture file` and `environment file s <orientation>` commands, and what they share with
// meshes that name their own textures: finding an input next to the scene file, reading each image
// once.
#include <algorithm>
#include <filesystem>

#include "hints.h"
#include "raylane/core/input_file.h"
#include "raylane/core/strings.h"
#include "raylane/image/input_image.h"
#include "raylane/scene/mesh_import.h"
#include "raylane/scene/orientation.h"
#include "raylane/scene/parse_state.h"
#include "raylane/scene/scene.h"

namespace raylane {

namespace fs = std::filesystem;

std::optional<std::string> find_input_file(const ParseState& state, const std::string& name) {
  std::vector<fs::path> candidates;
  fs::path p(name);
  if (p.is_absolute()) {
    candidates.push_back(p);
  } else {
    if (!state.scene_dir.empty()) candidates.push_back(fs::path(state.scene_dir) / p);
    candidates.push_back(p);
  }
  for (const auto& c : candidates) {
    std::error_code ec;
    if (fs::exists(c, ec)) return c.string();
  }
  return std::nullopt;
}

std::string where_looked(const ParseState& state, const std::string& name) {
  std::string where = state.scene_dir.empty()
                          ? std::string("the working directory")
                          : cat("'", state.scene_dir, "' and the working directory");
  return cat(quote_path(name), " not found (looked in ", where, ")");
}

namespace {

uint64_t memory_left(const ParseState& state) {
  uint64_t limit = state.options.image_memory, used = state.image_memory_used;
  return used < limit ? limit - used : 0;
}

// What reading the image at `path` takes, from its header: its texels and the decoder's peak.
struct ImageNeeds {
  SceneImage image;
  uint64_t decode = 0, file_bytes = 0;
};

Result<ImageNeeds> image_needs(const ParseState& state, const std::string& path, uint64_t extra) {
  auto info = read_input_image_info(path, memory_left(state));
  if (!info) return Error{info.error()};
  auto size = regular_file_size(path);
  if (!size) return Error{cat(path, ": ", size.error())};
  ImageNeeds n;
  n.image.file = path;
  n.image.width = info->width, n.image.height = info->height;
  n.image.kept = stored_texel_bytes(*info) + extra * uint64_t(info->width) * info->height;
  n.file_bytes = *size;
  n.decode = decode_texels_bytes(*info, *size);
  n.image.peak = std::max(n.decode, n.image.kept);
  return n;
}

// Why `render` refuses the image, or "": the decompression-bomb rule unless the user chose the
// image memory, then the image memory left.
std::string refusal(const ParseState& state, const ImageNeeds& n) {
  std::string what = cat("reading its ", n.image.width, "x", n.image.height, " pixels");
  if (!state.options.image_memory_chosen)
    if (auto bomb = decode_ratio_error(n.decode, n.file_bytes, state.images.wanted, what))
      return *bomb;
  if (n.image.peak > memory_left(state))
    return image_memory_error(n.image.peak, memory_left(state), what);
  return "";
}

// The texels at `path` within the image memory the scene has left, which they then take.
// Every image is checked from its header first and recorded (ParseState::images). A refused
// `texture` or `environment` line is an error, after which the scene cannot render, so the
// rest are read to their headers only, to find the image memory that reads them all; a refused
// texture of a mesh file is dropped (the caller warns), as is any image under --lenient. Only
// headers are read when the options ask for them (`raylane info`), and a refusal is then
// recorded, not an error. `extra` bytes per pixel are what the reader of the image builds from
// it besides (the environment's sampling tables).
Result<TexelImage> read_scene_texels(ParseState& state, const std::string& path, const FileLoc& at,
                                     SceneImage::Kind kind, uint64_t extra = 0) {
  auto needs = image_needs(state, path, extra);
  if (!needs) return Error{needs.error()};
  SceneImageMemory& mem = state.images;
  mem.wanted = std::max(mem.wanted, state.image_memory_used + needs->image.peak);
  needs->image.kind = kind;
  needs->image.refused = refusal(state, *needs);
  const bool refused = !needs->image.refused.empty();
  const bool fatal = kind != SceneImage::kMeshTexture && !state.options.lenient;
  if (refused && fatal && mem.first_refused.line == 0) mem.first_refused = at;
  const uint64_t left = memory_left(state);
  mem.images.push_back(needs->image);
  if (refused && !state.options.image_headers_only) {
    // Counted as if read when the scene cannot render (the figure after counts it); dropped
    // otherwise.
    if (fatal) state.image_memory_used += needs->image.kept;
    return Error{cat(path, ": ", needs->image.refused)};
  }
  state.image_memory_used += needs->image.kept;
  if (state.options.image_headers_only || mem.first_refused.line != 0) {
    TexelImage sized;
    sized.width = needs->image.width, sized.height = needs->image.height;
    return sized;
  }
  auto texels = read_input_texels(path, left, state.options.image_memory_chosen);
  if (!texels) {
    state.image_memory_used -= needs->image.kept;
    return texels;
  }
  // Float files that turn out to be halves take less than their header promised.
  uint64_t kept = texels->bytes() + extra * texels->texel_count();
  state.image_memory_used -= needs->image.kept - std::min(kept, needs->image.kept);
  mem.images.back().kept = kept;
  return texels;
}

// The environment's importance sampling: a fixed-point CDF entry per pixel, and its guide
// table's share (render/lights/environment.h). The light shares the scene's texels. (Each row's
// table adds about 70 bytes, not counted: 0.3 MB for the largest sky the limits allow.)
constexpr uint64_t kEnvironmentExtraBytes = sizeof(uint32_t) + 1;

}  // namespace

// The row of Scene::textures holding the image at `path`, read now if it is new.
Result<uint32_t> texture_row(Scene& s, ParseState& state, const std::string& path,
                             const FileLoc& at, bool of_mesh) {
  for (const auto& [file, row] : state.texture_files)
    if (file == path) return row;
  auto texels =
      read_scene_texels(state, path, at, of_mesh ? SceneImage::kMeshTexture : SceneImage::kTexture);
  if (!texels) return Error{texels.error()};
  s.textures.push_back(state.options.image_headers_only
                           ? Texture{path, std::move(*texels), glm::dvec3(0, 0, 0)}
                           : make_texture(path, std::move(*texels)));
  uint32_t row = uint32_t(s.textures.size() - 1);
  state.texture_files.emplace_back(path, row);
  state.input_files.push_back(path);
  return row;
}

Result<uint32_t> embedded_texture_row(Scene& s, ParseState& state, const MeshTexture& t) {
  for (const auto& [file, row] : state.texture_files)
    if (file == t.name) return row;
  Result<TexelImage> texels = Error{"it is empty or has more than 2^28 pixels"};
  if (t.texels != nullptr) {
    texels = float_texels(*t.texels);
  } else if (!t.file_bytes.empty()) {
    // The extension names the format for TGA only; the others are known by their contents.
    texels = decode_input_texels(t.file_bytes, cat("embedded.", t.extension), memory_left(state),
                                 state.options.image_memory_chosen);
  }
  if (!texels) return Error{texels.error()};
  uint64_t kept = texels->bytes();
  if (kept > memory_left(state))
    return Error{image_memory_error(kept, memory_left(state), "keeping it")};
  state.image_memory_used += kept;
  state.images.wanted = std::max(state.images.wanted, state.image_memory_used);
  state.images.images.push_back(
      {t.name, SceneImage::kMeshTexture, texels->width, texels->height, kept, kept, ""});
  s.textures.push_back(make_texture(t.name, std::move(*texels)));
  uint32_t row = uint32_t(s.textures.size() - 1);
  state.texture_files.emplace_back(t.name, row);
  return row;
}

bool texture_command(Scene& s, const Line& line, ParseState& state) {
  if (line.tokens.size() != 2) {
    state.problem(line.at(line.tokens.size() < 2 ? 1 : 2),
                  cat("texture takes one file name, found ", line.tokens.size() - 1, " parameters",
                      spaced_name_hint(line, 1, state)));
    return false;
  }
  if (!state.current_material) {
    state.problem(line.at(0),
                  "texture before any material line: it attaches to the current brdf or light");
    return false;
  }
  std::string name = line.tokens[1].name();
  auto path = find_input_file(state, name);
  if (!path) {
    state.problem(line.at(1), cat("texture ", where_looked(state, name)));
    return false;
  }
  auto row = texture_row(s, state, *path, line.at(1), false);
  if (!row) {
    state.problem(line.at(1), cat("cannot use texture ", quote_path(name), ": ", row.error()));
    return false;
  }
  Material& m = s.materials[*state.current_material];
  if (m.texture >= 0)
    state.diagnostics.warning(
        line.at(0), cat("the material already has texture ", quote_path(s.textures[m.texture].file),
                        ": this one replaces it"));
  m.texture = int32_t(*row);
  return true;
}

bool spaced_name(const Line& line, ParseState& state, std::string_view number);  // mesh_command.cpp

// `environment file s <orientation>`.
bool environment_command(Scene& s, const Line& line, ParseState& state) {
  if (line.tokens.size() < 3) {
    state.problem(line.at(line.tokens.size()),
                  cat("environment takes a file name and a scale s, found ", line.tokens.size() - 1,
                      " parameters"));
    return false;
  }
  if (spaced_name(line, state, "s")) return false;
  auto scale = parse_number(line, 2, state);
  if (!scale) return false;
  if (!positive_in_float(*scale, "environment scale", line, 2, state)) return false;
  auto rotation = parse_orientation(line, 3, state);
  if (!rotation) return false;
  std::string name = line.tokens[1].name();
  auto path = find_input_file(state, name);
  if (!path) {
    state.problem(line.at(1), cat("environment ", where_looked(state, name)));
    return false;
  }
  auto texels =
      read_scene_texels(state, *path, line.at(1), SceneImage::kEnvironment, kEnvironmentExtraBytes);
  if (!texels) {
    state.problem(line.at(1),
                  cat("cannot use environment ", quote_path(name), ": ", texels.error()));
    return false;
  }
  note_repeat(state.environment_at, line, state);
  state.input_files.push_back(*path);
  s.environment = EnvironmentSpec{*path, std::make_shared<const TexelImage>(std::move(*texels)),
                                  *scale, *rotation};
  return true;
}

void Scene::resolve_textures() {
  for (Material& m : materials) {
    if (m.mesh_copy_of >= 0 && materials[m.mesh_copy_of].texture >= 0)
      m.texture = materials[m.mesh_copy_of].texture;
    // A `microfacet` line after the mesh line applies to its copies too.
    if (m.mesh_copy_of >= 0) m.microfacet = materials[m.mesh_copy_of].microfacet;
  }
  TriangleTable& tri = table<Triangle>();
  if (!tri.has_uv()) return;
  for (uint32_t mat : tri.material)
    if (materials[mat].texture >= 0) return;
  tri.drop_uv_columns();
}

}  // namespace raylane
