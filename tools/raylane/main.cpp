// raylane: renders CS500 scenes. `raylane --help` lists the commands.
#include <cstdio>
#include <string>
#include <vector>

#include "commands.h"

namespace {

constexpr const char* kUsage = R"(raylane — a data-oriented SIMD ray tracer for CS500 scenes

usage:
  raylane render [SCENE] [options]   render SCENE (default: the built-in course test scene)
  raylane info [SCENE] [--lenient]   print what was modelled: tables, materials, lights, camera
  raylane trace MESH RAYS [options]  trace an external ray set (.rays) against a mesh (.tris
                                     or any mesh file), print the median Mrays/s, write .hits
  raylane convert IN OUT [--exposure E]  turn an .hdr/.pfm image into .hdr, .pfm or .png
  raylane diff IMAGE REF [--tol T]   RMSE, relMSE, mean and max difference of two .hdr/.pfm
                                     images; exit 1 when the RMSE is over T (default 0)
  raylane --help | --version

render options:
  -o, --output FILE   image to write; the extension picks the format: .hdr (Radiance RGBE),
                      .pfm (float), .png (8-bit sRGB). Repeat to write several.
                      Default: <scene name>.hdr in the working directory.
  --mode MODE         path | normal | depth | albedo | id | lit  (default: path)
  --spp N             path: samples per pixel, in progressive passes   (default: 16)
  --integrator I      path: brdf (BSDF sampling only) | nee (light sampling only) | mis
                      (both, power heuristic)                          (default: mis)
  --seed S            path: image seed; the image is the same for any --threads (default: 0)
  --max-depth D       path: at most D bounces (Russian roulette after 3)  (default: 64)
  --time SECONDS      path: stop after the pass that ends past this budget
  --checkpoint FILE   path: save the film to FILE every --checkpoint-every seconds (default
                      60) and when the render stops (done, --time, Ctrl-C)
  --resume FILE       path: continue a saved film up to --spp; same scene, --seed,
                      --integrator and --max-depth give the uninterrupted run's image
  --png               also write a PNG beside the first output
  --exposure E        PNG exposure in stops (pixel · 2^E)          (default: 0)
  --threads N         worker threads, 0 = all cores                (default: 0)
  --tracer T          packet (SIMD packets through the BVH) | bvh (single rays, double
                      kernels) | scalar (brute force, double kernels)  (default: packet)
  --isa I             sse4.2 | avx2 | avx512 | auto: the packet tracer's instruction set
  --traversal T       packets (W rays at a time) | rays (one at a time over 8-wide nodes) |
                      auto (packets for camera rays, rays for bounces)  (default: packets)
                                                                   (default: auto, the widest)
  --lenient           skip bad scene lines with a warning instead of failing
  --quiet             print only errors and the written image paths (no progress bar)

trace options (file formats: spec/ray-sets.md of the project's shared folder):
  -o, --output FILE   the answers (default: the ray set's name with .hits, here)
  --repeat N          runs to take the median of                   (default: 5)
  --traversal T       packets (W rays at a time, binary tree) | rays (one ray at a time,
                      8-wide tree; for incoherent rays)            (default: packets)
  --isa I, --threads N, --quiet   as for render

A path render shows a progress bar (on a terminal) and ends with a summary. The first Ctrl-C
finishes the pass in flight and writes the image converged so far (RAYLANE_SPP in the HDR
header), exit status 130; a second Ctrl-C exits at once.

exit status: 0 done, 1 failed while working (e.g. cannot write), 2 bad input or usage,
             130 interrupted (image written)
)";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h" || args[0] == "help")) {
    std::fputs(kUsage, stdout);
    return raylane::cli::kExitOk;
  }
  if (!args.empty() && args[0] == "--version") {
    std::printf("raylane %s\n", RAYLANE_VERSION);
    return raylane::cli::kExitOk;
  }
  if (args.empty()) return raylane::cli::render_command({});
  std::string command = args[0];
  std::vector<std::string> rest(args.begin() + 1, args.end());
  if (command == "render") return raylane::cli::render_command(rest);
  if (command == "info") return raylane::cli::info_command(rest);
  if (command == "trace") return raylane::cli::trace_command(rest);
  if (command == "convert") return raylane::cli::convert_command(rest);
  if (command == "diff") return raylane::cli::diff_command(rest);
  // `raylane scene.scn [options]` is short for `raylane render scene.scn [options]`.
  if (command.size() > 4 && command.substr(command.size() - 4) == ".scn")
    return raylane::cli::render_command(args);
  return raylane::cli::usage_error("unknown command '" + command + "'");
}
