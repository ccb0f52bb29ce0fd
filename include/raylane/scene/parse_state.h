// What Scene::command needs besides the line: options, where diagnostics go, and the state
// that carries from line to line (the current material, settings already seen).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/core/limits.h"
#include "raylane/core/memory.h"
#include "raylane/scene/mesh_summary.h"

namespace raylane {

struct Line;
struct Token;
struct CsgOpen;  // a csg block being read (csg_command.cpp)
struct SdfOpen;  // an sdf block being read (sdf_command.cpp)
struct Scene;

// Files that exist only in memory, by name (the built-in scene's meshes).
using MemoryFiles = std::vector<std::pair<std::string, std::string>>;

struct ParseOptions {
  bool lenient = false;  // errors on a line become warnings and the line is skipped
  const MemoryFiles* memory_files = nullptr;
  // Scene lines read after the file's own (`raylane render --set LINE`), with the file's rules:
  // the last camera or screen wins, with a warning. Diagnostics name them "--set:N:COL", N
  // counting the overrides from 1.
  std::vector<std::string> overrides;
  // What decoding the scene's textures and environment may take in all (core/limits.h), and
  // whether the user chose it (--image-memory), which lifts the decompression-bomb rule.
  uint64_t image_memory = default_image_memory();
  bool image_memory_chosen = false;
  // Read only the images' headers (`raylane info`): textures and the environment get their
  // size but no pixels (an Image whose rgb is empty), so such a scene describes, never renders.
  bool image_headers_only = false;
};

inline constexpr const char* kOverridesName = "--set";

// One image a scene reads (a texture or its environment), as its header describes it, for the
// image-memory checks and `raylane info`.
struct SceneImage {
  // A mesh file's texture: render drops it when refused, and goes on.
  enum Kind { kTexture, kEnvironment, kMeshTexture };
  std::string file;
  Kind kind = kTexture;
  uint32_t width = 0, height = 0;
  uint64_t kept = 0;    // its texels (and the environment's sampling tables) once read
  uint64_t peak = 0;    // the most its reading holds at once, its texels included
  std::string refused;  // why `render` refuses it; empty when it fits
};

struct SceneImageMemory {
  std::vector<SceneImage> images;
  // The image memory that reads every image so far: the largest of each image's peak above
  // the images kept before it. The figure a refusal's message gives.
  uint64_t wanted = 0;
  FileLoc first_refused;  // the first `texture` or `environment` line refused (line 0: none)
};

struct ParseState {
  ParseOptions options;
  Diagnostics diagnostics;
  std::string scene_dir;  // mesh paths are looked up here first, then in the working dir
  std::vector<std::string> input_files;  // every file read so far: meshes and what they name
  std::vector<MeshSummary> meshes;       // one per `mesh` line that imported
  std::optional<uint32_t> current_material;
  std::optional<uint32_t> brdf_material;        // the material of the latest brdf line
  std::optional<uint32_t> microfacet_material;  // the material of the latest microfacet line
  FileLoc microfacet_at;                        // and where that line is
  std::vector<std::pair<std::string, uint32_t>> texture_files;  // file found → Scene::textures row
  uint64_t image_memory_used = 0;  // by the textures and the environment read so far
  SceneImageMemory images;         // each image's needs, and what they all need
  // Where each command that may be given once was first seen; line 0: not yet.
  FileLoc screen_at, camera_at, ambient_at, lens_at, environment_at;
  // The last camera line that was rejected (line 0: none): its error already says what is
  // wrong, so no "no camera line" follows it.
  FileLoc camera_rejected_at;
  // The csg block whose `end` has not been read yet; null outside a block.
  std::shared_ptr<CsgOpen> csg_block;
  // The sdf block whose `end` has not been read yet; null outside a block.
  std::shared_ptr<SdfOpen> sdf_block;

  // Reports a problem with the line: an error, or a warning under --lenient.
  void problem(const FileLoc& loc, std::string message);
};

// At the end of the input: a csg block still open is a problem at its `csg` line.
void csg_end_of_input(ParseState& state);
// Likewise for an sdf block, whose leaves written so far are dropped from the scene.
void sdf_end_of_input(Scene& s, ParseState& state);

// For a command that may be given once: a repeat warns "the last one wins" and names the
// first; `seen` becomes this line.
void note_repeat(FileLoc& seen, const Line& line, ParseState& state);

// Where an input a line names is found: "relative to the directory of the scene file first,
// then the working directory"; an absolute path as it is. The first path that exists is taken,
// whatever it is (a reader then says if it is no regular file, rather than "not found").
std::optional<std::string> find_input_file(const ParseState& state, const std::string& name);
// "'a.png' (looked in 'dir' and the working directory)", for a not-found message.
std::string where_looked(const ParseState& state, const std::string& name);

// Reads one token as a number: a complete decimal float that is finite and fits in a float
// (docs/scene-language.md, "Lines and tokens"). Under --lenient a numeric prefix is taken
// with a warning. Reports and returns nullopt otherwise.
std::optional<double> parse_number(const Line& line, std::size_t token, ParseState& state);

// Reads tokens [first, first + count) as numbers, after checking that the line holds exactly
// that many more tokens (`exact`) or at least that many. Reports the first problem.
// A parameter that must be > 0, by the language's rule for numbers: it is read as a float, so
// one that rounds to 0 there (1e-46) is 0 (docs/scene-language.md, "Lines and tokens"). Reports
// "WHAT must be > 0" or "WHAT rounds to 0 in single precision; ..." at the token otherwise.
bool positive_in_float(double v, std::string_view what, const Line& line, std::size_t token,
                       ParseState& state);

std::optional<std::vector<double>> parse_numbers(const Line& line, std::size_t first,
                                                 std::size_t count, bool exact, ParseState& state);

}  // namespace raylane
