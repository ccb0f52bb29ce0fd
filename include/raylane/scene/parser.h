// Reading scene files: text → Scene, with every problem reported as file:line:col.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "raylane/scene/parse_state.h"
#include "raylane/scene/scene.h"

namespace raylane {

struct ParsedScene {
  Scene scene;
  Diagnostics diagnostics;
  // Every file the scene was read from: the scene file, its meshes and the files they name
  // (outputs must be none of them).
  std::vector<std::string> input_files;
  std::vector<MeshSummary> meshes;  // one per `mesh` line, in order
  SceneImageMemory images;          // the textures and the environment, as read or refused
  bool ok() const { return diagnostics.error_count() == 0; }
};

// Limits on input, checked before anything is allocated for it.
inline constexpr std::size_t kMaxSceneFileBytes = std::size_t(1) << 30;
inline constexpr std::size_t kMaxLineBytes = std::size_t(1) << 16;

// Parses scene text; `filename` names it in diagnostics, and its folder is where meshes are
// looked up first.
ParsedScene parse_scene(std::string_view text, const std::string& filename,
                        const ParseOptions& options = {});
// Reads and parses a scene file.
ParsedScene load_scene_file(const std::string& path, const ParseOptions& options = {});
// The built-in default: the course's test scene with its meshes, compiled into the program.
ParsedScene load_builtin_scene(const ParseOptions& options = {});
inline constexpr const char* kBuiltinSceneName = "<built-in testscene.scn>";

// Where a line cannot be split into tokens: the 1-based column and what is wrong.
struct TokenError {
  int col = 0;
  std::string message;
};

// Splits one line into tokens (whitespace: space, tab, CR; a token starting with '#' ends
// the line). The file name of `mesh`, `texture` and `environment` (the second token) may be
// double-quoted to hold spaces, with \" and \\ as escapes (docs/scene-language.md, "Lines and
// tokens"). Exposed for tests.
std::optional<TokenError> split_tokens(std::string_view text, std::vector<Token>& out);

}  // namespace raylane
