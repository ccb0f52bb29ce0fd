// `microfacet NAME`: the current brdf material's microfacet distribution (docs/microfacet.md).
#include "raylane/core/strings.h"
#include "raylane/scene/parse_state.h"
#include "raylane/scene/scene.h"

namespace raylane {

std::optional<Microfacet> microfacet_named(std::string_view name) {
  if (name == "phong") return Microfacet::kPhong;
  if (name == "ggx") return Microfacet::kGgx;
  if (name == "beckman") return Microfacet::kBeckman;
  return std::nullopt;
}

const char* microfacet_name(Microfacet m) {
  switch (m) {
    case Microfacet::kGgx:
      return "ggx";
    case Microfacet::kBeckman:
      return "beckman";
    case Microfacet::kPhong:
      break;
  }
  return "phong";
}

bool microfacet_command(Scene& s, const Line& line, ParseState& state) {
  if (line.tokens.size() != 2) {
    state.problem(line.at(line.tokens.size() < 2 ? 1 : 2),
                  cat("microfacet takes one name (phong, ggx or beckman), found ",
                      line.tokens.size() - 1, " parameters"));
    return false;
  }
  std::string_view name = line.tokens[1].text;
  auto kind = microfacet_named(name);
  if (!kind) {
    state.problem(line.at(1),
                  cat("microfacet takes phong, ggx or beckman, found ", in_quotes(name)));
    return false;
  }
  if (!state.current_material || state.current_material != state.brdf_material) {
    bool light = state.current_material && s.materials[*state.current_material].is_light;
    state.problem(line.at(0), light ? "microfacet after a light line: a light has no microfacets"
                                    : "microfacet before any brdf line: it sets the current "
                                      "brdf material's distribution");
    return false;
  }
  if (state.microfacet_material == state.current_material)
    state.diagnostics.warning(line.at(0),
                              cat("the material already has a microfacet line at ",
                                  to_string(state.microfacet_at), ": this one replaces it"));
  state.microfacet_material = state.current_material;
  state.microfacet_at = line.at(0);
  s.materials[*state.current_material].microfacet = *kind;
  return true;
}

}  // namespace raylane
