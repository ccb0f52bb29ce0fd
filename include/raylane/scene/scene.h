// The scene: one SoA table per primitive kind, materials, lights, camera and screen. Rows are
// appended by Scene::command, one parsed line at a time (docs/design.md, "Tables, not objects").
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/core/limits.h"
#include "raylane/core/rotation.h"
#include "raylane/prims/prim_list.h"
#include "raylane/scene/material.h"
#include "raylane/scene/texture.h"

namespace raylane {

struct CameraSpec {
  glm::dvec3 eye{};
  double ry = 1.0;           // tan(half the vertical field of view)
  glm::dmat3 rotation{1.0};  // right = R·x, up = R·y, forward = R·(−z)
};

// Thin-lens depth of field (`lens r d`): aperture radius and the distance from the eye to the
// plane in focus, along the forward axis. radius 0 is the pinhole.
struct LensSpec {
  double radius = 0;
  double focus = 1;
};

// An environment light (`environment file s <orientation>`): the image as read (texels, top row
// first; shared with the light that samples it, never copied), its scale s > 0 and the
// orientation R that turns the image's directions into the world (docs/scene-language.md,
// "Equirectangular environment mapping").
struct EnvironmentSpec {
  std::string file;
  std::shared_ptr<const TexelImage> texels;  // never null; no texels when only the header was read
  double scale = 1;
  glm::dmat3 rotation{1.0};
};

struct Token {
  std::string_view text;  // as written (with the quotes of a quoted file name)
  int col = 0;            // 1-based column of its first character
  std::string unquoted;   // a quoted file name without its quotes and escapes
  bool quoted = false;

  // The token as a file name: unquoted if it was quoted.
  std::string name() const { return quoted ? unquoted : std::string(text); }
};

// One non-blank, non-comment line of a scene file, split into tokens.
struct Line {
  std::vector<Token> tokens;
  FileLoc loc;                          // file and line; col = 0
  FileLoc at(std::size_t token) const;  // the location of a token (or of the line's end)
};

struct ParseState;

struct Scene {
  static constexpr uint32_t kDefaultWidth = 400, kDefaultHeight = 300;

  uint32_t width = kDefaultWidth, height = kDefaultHeight;
  std::optional<CameraSpec> camera;
  LensSpec lens;
  glm::vec3 ambient{0.0f, 0.0f, 0.0f};
  std::vector<Material> materials;
  std::vector<Texture> textures;  // images the materials refer to, each file once
  PrimTables tables;
  std::vector<PrimRef> lights;  // every primitive whose material emits
  std::optional<EnvironmentSpec> environment;

  template <class Kind>
  typename Kind::Table& table() {
    return std::get<kind_index<Kind>()>(tables);
  }
  template <class Kind>
  const typename Kind::Table& table() const {
    return std::get<kind_index<Kind>()>(tables);
  }
  std::size_t primitive_count() const;
  // Whether anything moves during the shutter (an `mbsphere`): only then do the paths draw a
  // time and the rays carry one (docs/motion-blur.md).
  bool moves() const { return table<MovingSphere>().size() > 0; }
  Bounds3f bounds() const;  // of every primitive (empty for none)
  uint32_t material_of(PrimRef ref) const;

  // Reorders the rows of every table: new row i of kind k is old row order[k][i] (order[k] is
  // a permutation of table k's rows, k = kind_index); the lights follow their rows.
  void permute(const std::vector<std::vector<uint32_t>>& order);

  // Validates one line and applies it: a setting, a material, or rows appended to a table.
  // Problems go to state.diagnostics; returns false if the line was rejected.
  bool command(const Line& line, ParseState& state);

  // After the last line: mesh materials' copies take their material's own `texture`, and the
  // triangles' UV columns go if no triangle's material is textured.
  void resolve_textures();
};

}  // namespace raylane
