#include <cstdio>

#include "args.h"
#include "commands.h"
#include "file_kind.h"

namespace raylane::cli {

int usage_error(const std::string& message) {
  std::fprintf(stderr, "raylane: %s\n(see raylane --help)\n", message.c_str());
  return kExitUsage;
}

int usage_error(const std::string& command, const std::string& message) {
  std::fprintf(stderr, "raylane: %s\n(see raylane %s --help)\n", message.c_str(), command.c_str());
  return kExitUsage;
}

Status read_image_memory_option(const std::string& value, uint64_t& bytes, bool& chosen) {
  long mib = 0;
  if (Status s = read_int_option("image-memory", value, 1, long(1) << 30, mib); !s) return s;
  bytes = uint64_t(mib) << 20;
  chosen = true;
  return ok_status();
}

std::optional<ParsedScene> load_scene_for_cli(const std::optional<std::string>& path, bool lenient,
                                              bool quiet, const std::vector<std::string>& overrides,
                                              SceneImages images) {
  // A film, a mesh, an image or another renderer's scene: one line that says so, not an error
  // for each of its lines.
  if (auto foreign = path ? not_a_scene(*path) : std::nullopt) {
    std::fprintf(stderr, "%s\n", foreign->c_str());
    return std::nullopt;
  }
  ParseOptions opts;
  opts.image_memory = images.memory;
  opts.image_memory_chosen = images.chosen;
  opts.image_headers_only = images.headers_only;
  opts.lenient = lenient;
  opts.overrides = overrides;
  ParsedScene parsed = path ? load_scene_file(*path, opts) : load_builtin_scene(opts);
  for (const Diagnostic& d : parsed.diagnostics.items)
    if (d.severity == Severity::kError || !quiet)
      std::fprintf(stderr, "%s\n", to_string(d).c_str());
  if (int more = parsed.diagnostics.dropped(); more > 0)
    std::fprintf(stderr, "raylane: %d more diagnostic%s not shown\n", more, more == 1 ? "" : "s");
  if (!parsed.ok()) {
    std::fprintf(stderr, "raylane: %d error%s in the scene; nothing rendered\n",
                 parsed.diagnostics.error_count(),
                 parsed.diagnostics.error_count() == 1 ? "" : "s");
    return std::nullopt;
  }
  return parsed;
}

}  // namespace raylane::cli
