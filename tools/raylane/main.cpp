// raylane: renders CS500 scenes. `raylane --help` lists the commands.
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include "commands.h"
#include "render_request.h"

namespace {

constexpr const char* kUsage = R"(raylane — a data-oriented SIMD ray tracer for CS500 scenes

usage:
  raylane render [SCENE] [options]   render SCENE (default: the built-in course test scene)
  raylane info [SCENE] [--lenient]   print what was modelled: tables, materials, lights, camera
                                     (or a mesh's triangles, or a film's size, spp and seed)
  raylane view [SCENE] [options]     look around SCENE in a window, path traced progressively;
                                     V prints the camera line, S saves the image
  raylane trace MESH RAYS [options]  trace an external ray set (.rays) against a mesh (.tris
                                     or any mesh file), print the median Mrays/s, write .hits
  raylane convert IN OUT [--exposure E] [--half]
                                     turn an .hdr/.pfm/.exr image into .hdr, .pfm, .png or .exr
  raylane diff IMAGE REF [--tol T]   RMSE, relMSE, mean and max difference of two .hdr/.pfm/.exr
                                     images; exit 1 when the RMSE is over T (default 0)
  raylane SCENE.scn [options]        short for raylane render SCENE.scn [options]
  raylane COMMAND --help             the command's options, each with its default
  raylane --help | --version

exit status: 0 done, 1 failed while working (e.g. cannot write), 2 bad input or usage,
             130 interrupted (image written)

Documents: docs/ in the repository (docs/README.md lists them).
)";

int run(const std::vector<std::string>& args) {
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h" || args[0] == "help")) {
    std::fputs(kUsage, stdout);
    return raylane::cli::kExitOk;
  }
  if (!args.empty() && args[0] == "--version") {
    std::printf("raylane %s\n", RAYLANE_VERSION);
    return raylane::cli::kExitOk;
  }
  // Bare `raylane` is someone finding out what it does: the usage, never a render that writes
  // over ./testscene.hdr (`raylane render` renders the built-in scene).
  if (args.empty()) {
    std::fputs(kUsage, stderr);
    return raylane::cli::kExitUsage;
  }
  std::string command = args[0];
  std::vector<std::string> rest(args.begin() + 1, args.end());
  if (command == "render") return raylane::cli::render_command(rest);
  if (command == "info") return raylane::cli::info_command(rest);
  if (command == "trace") return raylane::cli::trace_command(rest);
  if (command == "convert") return raylane::cli::convert_command(rest);
  if (command == "diff") return raylane::cli::diff_command(rest);
  if (command == "view") return raylane::cli::view_command(rest);
  // `raylane scene.scn [options]` is short for `raylane render scene.scn [options]`.
  if (command.size() > 4 && command.substr(command.size() - 4) == ".scn")
    return raylane::cli::render_command(args);
  return raylane::cli::usage_error("unknown command '" + command + "'");
}

}  // namespace

// Sizes an input announces are checked before they are allocated (a film, textures, meshes
// within their budget, and what writing a render's files takes); an allocation that fails all
// the same ends in this message, naming the files written before it, exit 2, never in
// std::terminate's abort.
int main(int argc, char** argv) {
  try {
    return run(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::bad_alloc&) {
    const std::vector<std::string>& written = raylane::cli::files_written();
    std::string files;
    for (const std::string& f : written)
      files += (files.empty() ? "" : ", ") + f;
    std::fprintf(stderr, "raylane: out of memory; %s\n",
                 written.empty() ? "nothing written" : ("written before it: " + files).c_str());
    return raylane::cli::kExitUsage;
  }
}
