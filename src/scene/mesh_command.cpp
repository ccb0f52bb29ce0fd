// The `mesh file tx ty tz s <orientation>` command: find the file, import it, place it.
#include <filesystem>

#include "raylane/core/strings.h"

#include "raylane/scene/mesh_import.h"
#include "raylane/scene/orientation.h"
#include "raylane/scene/parse_state.h"
#include "raylane/scene/scene.h"

namespace raylane {

namespace {

namespace fs = std::filesystem;

const std::string* find_memory_file(const ParseState& state, const std::string& name) {
  if (!state.options.memory_files) return nullptr;
  for (const auto& [n, bytes] : *state.options.memory_files)
    if (n == name) return &bytes;
  return nullptr;
}

// "A mesh path is looked up relative to the directory of the scene file first, then the
// working directory." The first path that exists is taken, whatever it is: the import then
// says if it is no regular file (a FIFO, a directory), rather than "not found".
std::optional<std::string> find_mesh_file(const ParseState& state, const std::string& name) {
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

Result<MeshImportStats> import(const ParseState& state, const std::string& name,
                               const MeshPlacement& placement, uint32_t material,
                               TriangleTable& table) {
  if (const std::string* bytes = find_memory_file(state, name))
    return import_mesh_memory(*bytes, name, placement, material, table);
  auto path = find_mesh_file(state, name);
  if (!path) {
    std::string where = state.scene_dir.empty()
                            ? std::string("the working directory")
                            : cat("'", state.scene_dir, "' and the working directory");
    return Error{cat("mesh file ", quote_path(name), " not found (looked in ", where, ")")};
  }
  return import_mesh_file(*path, placement, material, table);
}

}  // namespace

bool mesh_command(Scene& s, const Line& line, ParseState& state) {
  if (line.tokens.size() < 6) {
    state.problem(line.at(0), cat("mesh takes a file name and 4 numbers (tx ty tz s), found ",
                                  line.tokens.size() - 1, " parameters"));
    return false;
  }
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
  auto stats = import(state, name, placement, mat, table);
  if (!stats) {
    state.problem(line.at(1), stats.error());
    return false;
  }
  state.input_files.insert(state.input_files.end(), stats->files.begin(), stats->files.end());
  MeshSummary summary{name, line.loc, stats->triangles, stats->degenerate_dropped, {}};
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
  if (stats->degenerate_dropped > 0)
    state.diagnostics.warning(line.at(1), cat("skipped ", stats->degenerate_dropped,
                                              " zero-area triangles of ", quote_path(name)));
  if (s.materials[mat].is_light)
    for (uint32_t r = first_row; r < table.size(); ++r)
      s.lights.push_back(PrimRef(tag_of<Triangle>, r));
  return true;
}

}  // namespace raylane
