// The subcommands of the `raylane` program. Each returns the process exit status:
// 0 success, 1 a failure while working (e.g. the image could not be written), 2 bad input
// or usage.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "raylane/core/memory.h"
#include "raylane/scene/parser.h"

namespace raylane::cli {

inline constexpr int kExitOk = 0, kExitFailure = 1, kExitUsage = 2;

int render_command(const std::vector<std::string>& args);
int info_command(const std::vector<std::string>& args);
int trace_command(const std::vector<std::string>& args);
int convert_command(const std::vector<std::string>& args);
int diff_command(const std::vector<std::string>& args);
int view_command(const std::vector<std::string>& args);  // the interactive viewer (SDL2)

// How a command loads its scene besides --lenient and --set: the image memory (--image-memory)
// and whether images are read only to their headers (`raylane info`).
struct SceneImages {
  uint64_t memory = default_image_memory();
  bool headers_only = false;
  bool chosen = false;  // by --image-memory: the decompression-bomb rule is lifted
};

// Loads SCENE (or the built-in default when none is given), printing every diagnostic to
// stderr. `overrides` are the --set lines, read after the scene's own. Returns nothing when the
// scene has errors.
std::optional<ParsedScene> load_scene_for_cli(const std::optional<std::string>& path, bool lenient,
                                              bool quiet,
                                              const std::vector<std::string>& overrides = {},
                                              SceneImages images = {});

// --image-memory MIB: its help, its default as help shows it, and the value read into bytes
// (`chosen` becomes true: the user's figure lifts the decompression-bomb rule).
inline constexpr const char* kImageMemoryHelp =
    "what reading images may take in all, in MiB: decoded texels, the\n"
    "decoders' memory and the environment's sampling tables, counted\n"
    "from each header before decoding. Setting it also lifts the rule\n"
    "that refuses an image decoding to over 1024 times its file's size";
inline constexpr const char* kImageMemoryDefault = "half the memory available";
Status read_image_memory_option(const std::string& value, uint64_t& bytes, bool& chosen);

// The --set option's help, shared by the commands that load a scene.
inline constexpr const char* kSetOptionHelp =
    "a scene line read after the scene's own (repeatable), e.g.\n"
    "--set 'screen 1920 1080' or a camera line; the last camera, screen,\n"
    "ambient, lens or environment wins, with a warning";

// "raylane: message" on stderr, plus a hint to --help for usage errors: the command's own
// (`see raylane render --help`) when one is named, else the program's.
int usage_error(const std::string& message);
int usage_error(const std::string& command, const std::string& message);

}  // namespace raylane::cli
