// Lines that `csg` and `sdf` blocks read alike (block_lines.h).
#include "block_lines.h"

#include "raylane/core/strings.h"

namespace raylane {

std::string opened_at(const FileLoc& at, const Line& line) {
  return at.file == line.loc.file ? cat("line ", at.line) : to_string(at);
}

std::string solids(uint32_t n) {
  return cat(n, n == 1 ? " solid" : " solids");
}

bool no_parameters(const Line& line, ParseState& state) {
  if (line.tokens.size() == 1) return true;
  state.problem(line.at(1),
                cat(line.tokens[0].text, " takes no parameters, found ", line.tokens.size() - 1));
  return false;
}

std::optional<uint32_t> leaf_material(Scene& s, const Line& line, ParseState& state,
                                      std::string_view block) {
  if (!state.current_material) {
    state.diagnostics.warning(line.at(0), cat(line.tokens[0].text,
                                              " before any material line: using grey diffuse "
                                              "(Kd 0.5, no specular)"));
    s.materials.push_back(Material::default_grey());
    state.current_material = uint32_t(s.materials.size() - 1);
  }
  if (s.materials[*state.current_material].is_light) {
    state.problem(line.at(0), cat(block,
                                  " leaf cannot emit: expected a brdf material, found the "
                                  "light made by the latest light line"));
    return std::nullopt;
  }
  return state.current_material;
}

}  // namespace raylane
