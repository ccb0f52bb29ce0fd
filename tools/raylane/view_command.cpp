// `raylane view`: parse options, load the scene, open the window (view_loop.cpp).
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "args.h"
#include "commands.h"
#include "raylane/core/memory.h"
#include "raylane/core/strings.h"
#include "region_option.h"
#include "view.h"

namespace raylane::cli {

namespace {

const std::vector<OptionSpec>& view_specs() {
  static const std::vector<OptionSpec> specs = {
      {"set", 0, "LINE", true, kSetOptionHelp, ""},
      {"lenient", 0, "", false, "skip bad scene lines with a warning instead of failing", ""},
      {"spp-limit", 0, "N", false,
       "path: stop adding passes when the film holds N samples per pixel", "4096"},
      {"threads", 0, "N", false, "worker threads, 0 = all cores", "0"},
      {"image-memory", 0, "MIB", false, kImageMemoryHelp, kImageMemoryDefault},
      {"pfm", 0, "", false,
       "S also writes view-NNNN.pfm (32-bit float: what raylane diff compares exactly)", ""},
      {"region", 0, "X0,Y0,X1,Y1", false,
       "render only this pixel rectangle (black around it), as render's\n"
       "--region; S saves the rectangle alone",
       "the whole screen"},
  };
  return specs;
}

const CommandHelp& view_help() {
  static const CommandHelp help{
      "raylane view [SCENE] [options]",
      "Shows SCENE (default: the built-in course test scene) in a window, path traced with\n"
      "`raylane render`'s defaults and refined one pass per frame while the camera stands still;\n"
      "while it moves, the `lit` ray-casting view stands in. The render has the scene's screen\n"
      "size, and so has the window, but for a screen larger than 1280x800: it is shown scaled\n"
      "down to fit (V prints and S saves the scene's size). After N passes, the image\n"
      "S saves is the one `raylane render SCENE --set '<screen>' --set '<camera>' --spp N`\n"
      "writes, bit for bit, with the lines V prints. Needs a display (X11 or Wayland).",
      &view_specs(),
      cat(kViewKeys,
          "\nThe title shows the mode, the samples per pixel, the rays per second and the frames\n"
          "per second (each frame's own time).\n"
          "The scene language: docs/scene-language.md.")};
  return help;
}

Result<ViewRequest> read_view_request(const std::vector<std::string>& args) {
  auto parsed = parse_args(args, view_specs());
  if (!parsed) return Error{parsed.error()};
  ViewRequest r;
  if (parsed->positional.size() > 1) return Error{"view takes at most one scene file"};
  if (!parsed->positional.empty()) r.scene_path = parsed->positional[0];
  if (parsed->has("set")) r.overrides = parsed->values.at("set");
  r.lenient = parsed->has("lenient");
  r.save_pfm = parsed->has("pfm");
  if (auto v = parsed->last("spp-limit"))
    if (Status s = read_int_option("spp-limit", *v, 1, 1 << 24, r.spp_limit); !s)
      return Error{s.error()};
  if (auto v = parsed->last("image-memory"))
    if (Status s = read_image_memory_option(*v, r.image_memory, r.image_memory_chosen); !s)
      return Error{s.error()};
  if (auto v = parsed->last("region"))
    if (Status s = read_region_option(*v, r.region); !s) return Error{s.error()};
  if (auto v = parsed->last("threads"))
    if (Status s = read_int_option("threads", *v, 0, 4096, r.threads); !s) return Error{s.error()};
  return r;
}

}  // namespace

int view_command(const std::vector<std::string>& args) {
  if (asks_for_help(args, view_specs())) return print_help(view_help());
  auto request = read_view_request(args);
  if (!request) return usage_error("view", request.error());
#ifndef RAYLANE_HAVE_SDL2
  std::fprintf(stderr,
               "raylane: this raylane was built without SDL2, so it has no `view` (install "
               "libsdl2-dev and build again)\n");
  return kExitUsage;
#else
  // Asked before the scene is loaded: without a display there is nothing to do with it.
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY") &&
      !std::getenv("SDL_VIDEODRIVER")) {
    std::fprintf(stderr,
                 "raylane: view needs a display, and neither DISPLAY nor WAYLAND_DISPLAY is set "
                 "(without one, try xvfb-run raylane view, or raylane render)\n");
    return kExitUsage;
  }
  auto parsed =
      load_scene_for_cli(request->scene_path, request->lenient, /*quiet=*/false, request->overrides,
                         {request->image_memory, false, request->image_memory_chosen});
  if (!parsed) return kExitUsage;
  if (Status s = region_fits(request->region, parsed->scene); !s)
    return usage_error("view", s.error());
  // The film's sums (3 doubles), the image shown and the one saved (3 floats each) and the
  // window's 8-bit pixels, per pixel of the scene's screen.
  const Scene& scene = parsed->scene;
  uint64_t bytes = uint64_t(scene.width) * scene.height * (24 + 12 + 12 + 4);
  if (Status s =
          check_memory(bytes, cat("the film of a ", scene.width, "x", scene.height, " view"));
      !s) {
    std::fprintf(stderr, "raylane: %s\n", s.error().c_str());
    return kExitUsage;
  }
  ViewSession session(*request, std::move(*parsed));
  std::string name = request->scene_path
                         ? std::filesystem::path(*request->scene_path).filename().string()
                         : std::string("built-in testscene.scn");
  return run_view_window(session, name);
#endif
}

}  // namespace raylane::cli
