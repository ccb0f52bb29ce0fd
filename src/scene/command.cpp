// Scene::command: one parsed line → a setting, a material, or rows in a table
// (docs/scene-language.md, "Commands").
#include <cmath>

#include "hints.h"
#include "raylane/core/strings.h"

#include "raylane/scene/mesh_import.h"
#include "raylane/scene/orientation.h"
#include "raylane/scene/parse_state.h"
#include "raylane/scene/scene.h"

namespace raylane {

namespace {

bool all_non_negative(const std::vector<double>& v, std::size_t first, std::size_t count) {
  for (std::size_t i = first; i < first + count; ++i)
    if (v[i] < 0) return false;
  return true;
}

glm::vec3 vec3f(const std::vector<double>& v, std::size_t i) {
  return {float(v[i]), float(v[i + 1]), float(v[i + 2])};
}

}  // namespace

// "Several screen/camera/ambient lines: the last one wins, with a warning."
void note_repeat(FileLoc& seen, const Line& line, ParseState& state) {
  if (seen.line != 0) {
    std::string first = seen.file == line.loc.file ? cat("on line ", seen.line)
                                                   : cat("at ", seen.file, ":", seen.line);
    state.diagnostics.warning(line.at(0), cat(line.tokens[0].text, " given again (first ", first,
                                              "): the last one wins"));
  }
  seen = line.loc;
}

namespace {

bool screen_command(Scene& s, const Line& line, ParseState& state) {
  auto v = parse_numbers(line, 1, 2, true, state);
  if (!v) return false;
  for (int i = 0; i < 2; ++i) {
    double x = (*v)[i];
    if (x < 1 || x != std::floor(x)) {
      state.problem(line.at(1 + i), "screen size must be a whole number >= 1");
      return false;
    }
    if (x > double(kMaxImagePixels)) {
      state.problem(line.at(1 + i), cat("screen side ", line.tokens[1 + i].text,
                                        " is more than 2^28 (268435456), the pixel limit"));
      return false;
    }
  }
  if ((*v)[0] * (*v)[1] > double(kMaxImagePixels)) {
    state.problem(line.at(1), cat("screen has ", uint64_t((*v)[0] * (*v)[1]),
                                  " pixels; the limit is 2^28 (268435456) pixels"));
    return false;
  }
  note_repeat(state.screen_at, line, state);
  s.width = uint32_t((*v)[0]);
  s.height = uint32_t((*v)[1]);
  return true;
}

bool camera_command(Scene& s, const Line& line, ParseState& state) {
  state.camera_rejected_at = line.loc;  // until the line is taken
  auto v = parse_numbers(line, 1, 4, false, state);
  if (!v) return false;
  if (!positive_in_float((*v)[3], "camera ry", line, 4, state)) return false;
  auto rot = parse_orientation(line, 5, state);
  if (!rot) return false;
  note_repeat(state.camera_at, line, state);
  state.camera_rejected_at = {};
  s.camera = CameraSpec{{(*v)[0], (*v)[1], (*v)[2]}, (*v)[3], *rot};
  return true;
}

bool lens_command(Scene& s, const Line& line, ParseState& state) {
  auto v = parse_numbers(line, 1, 2, true, state);
  if (!v) return false;
  if (!((*v)[0] >= 0)) {
    state.problem(line.at(1), "lens radius must be >= 0 (0 is the pinhole)");
    return false;
  }
  if (!positive_in_float((*v)[1], "lens focus distance", line, 2, state)) return false;
  note_repeat(state.lens_at, line, state);
  s.lens = LensSpec{(*v)[0], (*v)[1]};
  return true;
}

bool ambient_command(Scene& s, const Line& line, ParseState& state) {
  auto v = parse_numbers(line, 1, 3, true, state);
  if (!v) return false;
  note_repeat(state.ambient_at, line, state);
  s.ambient = vec3f(*v, 0);
  return true;
}

uint32_t add_material(Scene& s, const Material& m, ParseState& state) {
  s.materials.push_back(m);
  state.current_material = uint32_t(s.materials.size() - 1);
  return *state.current_material;
}

bool brdf_command(Scene& s, const Line& line, ParseState& state) {
  std::size_t found = line.tokens.size() - 1;
  if (found != 7 && found != 11) {
    state.problem(line.at(0),
                  cat("brdf takes 7 or 11 numbers, found ", found, comma_hint(line, 1)));
    return false;
  }
  auto v = parse_numbers(line, 1, found, true, state);
  if (!v) return false;
  if (!all_non_negative(*v, 0, 6) || (found == 11 && !all_non_negative(*v, 7, 3))) {
    state.problem(line.at(1), "brdf colours (Kd, Ks, Kt) must be >= 0");
    return false;
  }
  if ((*v)[6] < 0) {
    state.problem(line.at(7), "brdf alpha must be >= 0");
    return false;
  }
  Material m;
  m.kd = vec3f(*v, 0);
  m.ks = vec3f(*v, 3);
  m.alpha = float((*v)[6]);
  if (found == 11) {
    if (!((*v)[10] > 0)) {
      state.problem(line.at(11), "brdf ior must be > 0");
      return false;
    }
    m.kt = vec3f(*v, 7);
    m.ior = float((*v)[10]);
  }
  state.brdf_material = add_material(s, m, state);
  return true;
}

bool light_command(Scene& s, const Line& line, ParseState& state) {
  auto v = parse_numbers(line, 1, 3, true, state);
  if (!v) return false;
  if (!all_non_negative(*v, 0, 3)) {
    state.problem(line.at(1), "light radiance must be >= 0");
    return false;
  }
  Material m;
  m.kd = {0, 0, 0};
  m.emission = vec3f(*v, 0);
  m.is_light = true;
  add_material(s, m, state);
  return true;
}

// The current material; a shape before any material line gets the default grey one.
uint32_t shape_material(Scene& s, const Line& line, ParseState& state) {
  if (state.current_material) return *state.current_material;
  state.diagnostics.warning(line.at(0), cat(line.tokens[0].text,
                                            " before any material line: using grey diffuse "
                                            "(Kd 0.5, no specular)"));
  return add_material(s, Material::default_grey(), state);
}

template <class Kind>
bool primitive(Scene& s, const Line& line, ParseState& state) {
  auto v = parse_numbers(line, 1, Kind::param_count, true, state);
  if (!v) return false;
  auto& table = s.table<Kind>();
  if (table.size() >= PrimRef::kMaxRows) {
    state.problem(line.at(0), cat("too many ", Kind::plural));
    return false;
  }
  // Checked before the material, so a rejected line leaves no default material behind.
  typename Kind::Table scratch;
  auto params = std::span<const double, Kind::param_count>(v->data(), Kind::param_count);
  if (auto err = scratch.append(params, 0)) {
    state.problem(line.at(1 + std::max(err->param, 0)), err->message);
    return false;
  }
  uint32_t mat = shape_material(s, line, state);
  table.append(params, mat);
  if (s.materials[mat].is_light)
    s.lights.push_back(PrimRef(tag_of<Kind>, uint32_t(table.size() - 1)));
  return true;
}

}  // namespace

bool mesh_command(Scene& s, const Line& line, ParseState& state);
bool texture_command(Scene& s, const Line& line, ParseState& state);
bool environment_command(Scene& s, const Line& line, ParseState& state);
bool microfacet_command(Scene& s, const Line& line, ParseState& state);
bool csg_command(Scene& s, const Line& line, ParseState& state);
bool is_csg_word(std::string_view word);
bool sdf_command(Scene& s, const Line& line, ParseState& state);
bool is_sdf_word(std::string_view word);

bool Scene::command(const Line& line, ParseState& state) {
  std::string_view word = line.tokens[0].text;
  // An open block reads its lines; `end` and the operators go to the one open (csg first: an
  // sdf-only line in a csg block is an error there).
  if (state.csg_block) return csg_command(*this, line, state);
  if (state.sdf_block || is_sdf_word(word)) return sdf_command(*this, line, state);
  if (is_csg_word(word)) return csg_command(*this, line, state);
  if (word == "screen") return screen_command(*this, line, state);
  if (word == "camera") return camera_command(*this, line, state);
  if (word == "ambient") return ambient_command(*this, line, state);
  if (word == "lens") return lens_command(*this, line, state);
  if (word == "brdf") return brdf_command(*this, line, state);
  if (word == "light") return light_command(*this, line, state);
  if (word == "mesh") return mesh_command(*this, line, state);
  if (word == "texture") return texture_command(*this, line, state);
  if (word == "environment") return environment_command(*this, line, state);
  if (word == "microfacet") return microfacet_command(*this, line, state);
  bool handled = false, accepted = false;
  PrimKinds::for_each([&](auto kind) {
    using Kind = decltype(kind);
    if constexpr (Kind::param_count > 0) {
      if (!handled && word == Kind::keyword) {
        handled = true;
        accepted = primitive<Kind>(*this, line, state);
      }
    }
  });
  if (!handled)
    state.problem(line.at(0), cat("unknown command ", in_quotes(word), command_hint(word)));
  return accepted;
}

}  // namespace raylane
