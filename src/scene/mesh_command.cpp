// The `mesh file tx ty tz s <orientation>` command: find the file, import it, place it.
#include <algorithm>
#include <filesystem>

#include "hints.h"
#include "raylane/core/strings.h"

#include "raylane/scene/mesh_import.h"
#include "raylane/scene/orientation.h"
#include "raylane/scene/parse_state.h"
#include "raylane/scene/scene.h"

namespace raylane {

// texture_command.cpp: the row of Scene::textures for an image file, read once; for an image
// embedded in a mesh file, decoded once.
Result<uint32_t> texture_row(Scene& s, ParseState& state, const std::string& path,
                             const FileLoc& at, bool of_mesh);
Result<uint32_t> embedded_texture_row(Scene& s, ParseState& state, const MeshTexture& t);

namespace {

namespace fs = std::filesystem;

const std::string* find_memory_file(const ParseState& state, const std::string& name) {
  if (!state.options.memory_files) return nullptr;
  for (const auto& [n, bytes] : *state.options.memory_files)
    if (n == name) return &bytes;
  return nullptr;
}

Result<MeshImportStats> import(const ParseState& state, const std::string& name,
                               const MeshPlacement& placement, uint32_t material,
                               TriangleTable& table, const MaterialChooser& choose) {
  if (const std::string* bytes = find_memory_file(state, name))
    return import_mesh_memory(*bytes, name, placement, material, table);
  auto path = find_input_file(state, name);
  if (!path) return Error{cat("mesh file ", where_looked(state, name))};
  return import_mesh_file(*path, placement, material, table, choose);
}

// The materials a mesh file's own textures make (docs/scene-language.md, "UV conventions"):
// a copy of the line's material per texture, numbered after the scene's materials (and
// after the default one a mesh before any material line creates), and added to the scene only
// if the import succeeds. A texture that cannot be used is a warning: those triangles keep the
// line's material.
struct MeshTextures {
  Scene& scene;
  ParseState& state;
  const Line& line;
  uint32_t material;                                         // the line's material
  uint32_t next_index;                                       // the index the next copy gets
  std::vector<std::pair<uint32_t, uint32_t>> copies;         // (texture row, material index)
  std::vector<std::string> named;                            // each texture the file names, once
  std::vector<std::pair<std::string, std::string>> dropped;  // (name, why), once each

  uint32_t choose(const MeshTexture& texture) {
    if (texture.name.empty()) return material;
    bool first = std::find(named.begin(), named.end(), texture.name) == named.end();
    if (first) named.push_back(texture.name);
    for (const auto& [name, why] : dropped)
      if (name == texture.name) return material;  // refused once already: not read again
    auto row = texture.embedded ? embedded_texture_row(scene, state, texture)
                                : texture_row(scene, state, texture.name, line.at(1), true);
    if (!row) {
      dropped.emplace_back(texture.name, row.error());
      return material;
    }
    for (const auto& [tex, index] : copies)
      if (tex == *row) return index;
    copies.emplace_back(*row, next_index);
    return next_index++;
  }

  void warn(std::string message) { state.diagnostics.warning(line.at(1), std::move(message)); }

  // One warning for the textures dropped: how many of how many, which and why, and what the
  // triangles that named them show instead.
  void warn_dropped() {
    if (dropped.empty()) return;
    std::string mesh = quote_path(line.tokens[1].name());
    std::string which;
    for (const auto& [name, why] : dropped)
      which += cat(which.empty() ? "" : "; ", quote_path(name), " (", why, ")");
    bool all = dropped.size() == named.size();
    warn(cat("mesh ", mesh, ": ", dropped.size(), " of its ", counted(named.size(), "texture"),
             all ? " cannot be used, so the mesh renders untextured: "
                 : " cannot be used, so the triangles whose materials name ",
             all ? "" : (dropped.size() == 1 ? "it" : "them"),
             all ? "" : " render untextured with the line's material: ", which));
  }

  // After a successful import: the copies, in the order their indices were given.
  void add_copies() {
    for (const auto& [tex, index] : copies) {
      Material m = scene.materials[material];
      m.texture = int32_t(tex);
      m.mesh_copy_of = int32_t(material);
      scene.materials.push_back(m);
      (void)index;
    }
  }
};

// "skipped 2 faces of 'm.obj' that name a vertex, texture coordinate or normal it does not
// have (lines 6, 9)": at most five lines named, then how many more. (Lines and points, which
// raylane drops anyway, are counted with the faces.)
std::string obj_drop_warning(const std::vector<uint64_t>& lines, const std::string& name) {
  std::string listed;
  for (std::size_t i = 0; i < lines.size() && i < 5; ++i)
    listed += cat(i ? ", " : "", lines[i]);
  if (lines.size() > 5) listed += cat(" and ", lines.size() - 5, " more");
  const bool one = lines.size() == 1;
  return cat("skipped ", lines.size(), one ? " face" : " faces", " of ", quote_path(name),
             one ? " that names" : " that name",
             " a vertex, texture coordinate or normal it does not have (line", one ? " " : "s ",
             listed, ")");
}

}  // namespace

// A file name with a space left unquoted (`mesh my model.ply 0 0 0 1`) reads as a name and a
// token that is no number: said as such, with the quotes that mend it, when the joined name
// is a file and the first part is not. Shared with `environment` (texture_command.cpp).
// True when it reported one.
bool spaced_name(const Line& line, ParseState& state, std::string_view number) {
  if (line.tokens.size() < 3 || find_input_file(state, line.tokens[1].name())) return false;
  const std::string hint = spaced_name_hint(line, 1, state);
  if (hint.empty()) return false;
  state.problem(line.at(2), cat("expected a number (", number, ") after the file name, found ",
                                in_quotes(line.tokens[2].text), hint));
  return true;
}

bool mesh_command(Scene& s, const Line& line, ParseState& state) {
  if (line.tokens.size() < 6) {
    state.problem(line.at(0), cat("mesh takes a file name and 4 numbers (tx ty tz s), found ",
                                  line.tokens.size() - 1, " parameters"));
    return false;
  }
  if (spaced_name(line, state, "tx")) return false;
  auto v = parse_numbers(line, 2, 4, false, state);
  if (!v) return false;
  if (!((*v)[3] > 0)) {
    state.problem(line.at(5), "mesh scale must be > 0");
    return false;
  }
  auto rot = parse_orientation(line, 6, state);
  if (!rot) return false;
  MeshPlacement placement{{(*v)[0], (*v)[1], (*v)[2]}, (*v)[3], *rot};
  std::string name = line.tokens[1].name();
  TriangleTable& table = s.table<Triangle>();
  uint32_t first_row = uint32_t(table.size());
  // The material index is only committed (a default one created) if the import succeeds.
  bool had_material = state.current_material.has_value();
  uint32_t mat = had_material ? *state.current_material : uint32_t(s.materials.size());
  uint32_t first_copy = uint32_t(s.materials.size()) + (had_material ? 0 : 1);
  MeshTextures textures{s, state, line, mat, first_copy, {}, {}, {}};
  auto stats = import(state, name, placement, mat, table,
                      [&](const MeshTexture& texture) { return textures.choose(texture); });
  if (!stats) {
    state.problem(line.at(1), stats.error());
    return false;
  }
  state.input_files.insert(state.input_files.end(), stats->files.begin(), stats->files.end());
  MeshSummary summary{name,          line.loc, stats->triangles, stats->degenerate_dropped, mat,
                      stats->has_uv, {}};
  for (uint32_t r = first_row; r < table.size(); ++r)
    summary.bounds.extend(table.bounds(r));
  state.meshes.push_back(std::move(summary));
  if (!had_material) {
    state.diagnostics.warning(line.at(0),
                              "mesh before any material line: using grey diffuse "
                              "(Kd 0.5, no specular)");
    s.materials.push_back(Material::default_grey());
    state.current_material = mat;
  }
  textures.add_copies();
  textures.warn_dropped();
  if (stats->degenerate_dropped > 0)
    state.diagnostics.warning(line.at(1), cat("skipped ", stats->degenerate_dropped,
                                              " zero-area triangles of ", quote_path(name)));
  if (const auto& lines = stats->obj_lines_dropped; !lines.empty())
    state.diagnostics.warning(line.at(1), obj_drop_warning(lines, name));
  if (s.materials[mat].is_light)  // its copies emit too
    for (uint32_t r = first_row; r < table.size(); ++r)
      s.lights.push_back(PrimRef(tag_of<Triangle>, r));
  return true;
}

}  // namespace raylane
