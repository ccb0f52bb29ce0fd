// The `texture file` and `environment file s <orientation>` commands, and what they share with
// meshes that name their own textures: finding an input next to the scene file, reading each image
// once.
#include <filesystem>

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

// The image at `path` within the image memory the scene has left, which it then takes; only
// its size when the options ask for headers only. `extra` bytes per pixel are what the reader of
// the image builds from it besides (the environment's sampling tables).
Result<Image> read_scene_image(ParseState& state, const std::string& path, uint64_t extra = 0) {
  if (state.options.image_headers_only) {
    auto info = read_input_image_info(path, memory_left(state));
    if (!info) return Error{info.error()};
    Image sized;
    sized.width = info->width, sized.height = info->height;
    return sized;
  }
  auto image = read_input_image(path, memory_left(state));
  if (!image) return image;
  uint64_t kept =
      image->rgb.size() * sizeof(float) + extra * uint64_t(image->width) * image->height;
  if (kept > memory_left(state))
    return Error{cat(path, ": ", image_memory_error(kept, memory_left(state), "keeping it"))};
  state.image_memory_used += kept;
  return image;
}

// The environment's importance sampling: a luminance and a CDF entry (doubles) per pixel, and
// the copy of the image the light keeps.
constexpr uint64_t kEnvironmentExtraBytes = 2 * sizeof(double) + 3 * sizeof(float);

}  // namespace

// The row of Scene::textures holding the image at `path`, read now if it is new.
Result<uint32_t> texture_row(Scene& s, ParseState& state, const std::string& path) {
  for (const auto& [file, row] : state.texture_files)
    if (file == path) return row;
  auto image = read_scene_image(state, path);
  if (!image) return Error{image.error()};
  s.textures.push_back(state.options.image_headers_only
                           ? Texture{path, std::move(*image), glm::dvec3(0, 0, 0)}
                           : make_texture(path, std::move(*image)));
  uint32_t row = uint32_t(s.textures.size() - 1);
  state.texture_files.emplace_back(path, row);
  state.input_files.push_back(path);
  return row;
}

Result<uint32_t> embedded_texture_row(Scene& s, ParseState& state, const MeshTexture& t) {
  for (const auto& [file, row] : state.texture_files)
    if (file == t.name) return row;
  Result<Image> image = Error{"it is empty or has more than 2^28 pixels"};
  if (t.texels != nullptr) {
    image = *t.texels;
  } else if (!t.file_bytes.empty()) {
    // The extension names the format for TGA only; the others are known by their contents.
    image = decode_input_image(t.file_bytes, cat("embedded.", t.extension), memory_left(state));
  }
  if (!image) return Error{image.error()};
  uint64_t kept = image->rgb.size() * sizeof(float);
  if (kept > memory_left(state))
    return Error{image_memory_error(kept, memory_left(state), "keeping it")};
  state.image_memory_used += kept;
  s.textures.push_back(make_texture(t.name, std::move(*image)));
  uint32_t row = uint32_t(s.textures.size() - 1);
  state.texture_files.emplace_back(t.name, row);
  return row;
}

bool texture_command(Scene& s, const Line& line, ParseState& state) {
  if (line.tokens.size() != 2) {
    state.problem(
        line.at(line.tokens.size() < 2 ? 1 : 2),
        cat("texture takes one file name, found ", line.tokens.size() - 1, " parameters"));
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
  auto row = texture_row(s, state, *path);
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

// `environment file s <orientation>`.
bool environment_command(Scene& s, const Line& line, ParseState& state) {
  if (line.tokens.size() < 3) {
    state.problem(line.at(line.tokens.size()),
                  cat("environment takes a file name and a scale s, found ", line.tokens.size() - 1,
                      " parameters"));
    return false;
  }
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
  auto image = read_scene_image(state, *path, kEnvironmentExtraBytes);
  if (!image) {
    state.problem(line.at(1),
                  cat("cannot use environment ", quote_path(name), ": ", image.error()));
    return false;
  }
  note_repeat(state.environment_at, line, state);
  state.input_files.push_back(*path);
  s.environment = EnvironmentSpec{*path, std::move(*image), *scale, *rotation};
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
