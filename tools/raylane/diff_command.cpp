// `raylane diff IMAGE REFERENCE [--tol T] [--heatmap FILE]`: how far an image is from a
// reference — RMSE, relative MSE, mean and max absolute difference over all channels, and the
// pixel of the largest — and exit status 1 when the RMSE exceeds T (default 0: any
// difference), as pbrt's `imgtool diff` does for scripts; --heatmap writes the per-pixel
// relative error as an image.
#include <cstdio>

#include "args.h"
#include "commands.h"
#include "file_roles.h"
#include "image_reading.h"
#include "raylane/core/atomic_file.h"
#include "raylane/core/strings.h"
#include "raylane/image/metrics.h"
#include "raylane/image/write_image.h"

namespace raylane::cli {

namespace {
const std::vector<OptionSpec> kDiffOptions = {
    {"tol", 0, "T", false, "the largest RMSE that still counts as equal (exit status 0)", "0"},
    {"heatmap", 0, "FILE", false,
     "also write the per-pixel relative error sqrt(mean of (a−b)²/(b²+0.01))\n"
     "as an image (.hdr, .pfm, .exr keep it; as .png, 1 or more is white)",
     "none"},
    {"image-memory", 0, "MIB", false, kImageMemoryHelp, kImageMemoryDefault},
};
const CommandHelp kDiffHelp{
    "raylane diff IMAGE REFERENCE [--tol T] [--heatmap FILE] [--image-memory MIB]",
    "Prints how far IMAGE is from REFERENCE (the same size; .hdr, .pfm, .exr, or .png, .jpg,\n"
    ".tga, .bmp read as linear RGB) on one line of names and numbers: rmse, relmse (mean of\n"
    "(a−b)²/(b²+0.01)), mean_abs and max_abs over all channels, and max_x, max_y, max_channel:\n"
    "where the largest difference is (pixel column and row from the top left, channel 0-2).\n"
    "Exit status 1 when the RMSE is over T. The sizes are compared from the headers, before\n"
    "any pixel is decoded.",
    &kDiffOptions, ""};

// --heatmap: checked before any work, like every output (never over an input).
Status check_heatmap(const std::string& heatmap, const std::string& a, const std::string& ref) {
  auto format = format_from_path(heatmap);
  if (!format) return Error{format.error()};
  if (Status s = check_outputs_apart({{a, "the image"}, {ref, "the reference"}},
                                     {{heatmap, "the --heatmap image"}});
      !s)
    return s;
  if (Status s = check_writable(heatmap); !s)
    return Error{cat("cannot write --heatmap ", heatmap, ": ", s.error())};
  return ok_status();
}
}  // namespace

int diff_command(const std::vector<std::string>& args) {
  if (asks_for_help(args, kDiffOptions)) return print_help(kDiffHelp);
  auto parsed = parse_args(args, kDiffOptions);
  if (!parsed) return usage_error("diff", parsed.error());
  if (parsed->positional.size() != 2) return usage_error("diff", "diff takes IMAGE and REFERENCE");
  double tol = 0;
  if (auto t = parsed->last("tol")) {
    if (Status s = read_double_option("tol", *t, tol); !s) return usage_error("diff", s.error());
    if (!(tol >= 0)) return usage_error("diff", "--tol must be ≥ 0");
  }
  const std::string& a_path = parsed->positional[0];
  const std::string& ref_path = parsed->positional[1];
  ImageMemoryOption memory;
  if (auto v = parsed->last("image-memory"))
    if (Status s = read_image_memory_option(*v, memory.bytes, memory.chosen); !s)
      return usage_error("diff", s.error());
  auto heatmap = parsed->last("heatmap");
  if (heatmap)
    if (Status s = check_heatmap(*heatmap, a_path, ref_path); !s)
      return usage_error("diff", s.error());
  // Headers first: images of different sizes, or too large, are refused before decoding.
  auto ha = read_any_header(a_path);
  auto href = read_any_header(ref_path);
  for (const auto* h : {&ha, &href}) {
    if (h->ok()) continue;
    std::fprintf(stderr, "raylane: %s\n", h->error().c_str());
    return kExitUsage;
  }
  if (ha->width != href->width || ha->height != href->height) {
    std::fprintf(stderr, "raylane: %s is %ux%u and %s is %ux%u: images of different sizes\n",
                 a_path.c_str(), ha->width, ha->height, ref_path.c_str(), href->width,
                 href->height);
    return kExitUsage;
  }
  if (Status s = check_images_memory({*ha, *href}, heatmap ? ha->float_bytes() : 0, memory); !s) {
    std::fprintf(stderr, "raylane: %s\n", s.error().c_str());
    return kExitUsage;
  }
  auto a = read_any_image(*ha);
  auto ref = read_any_image(*href);
  for (const auto* img : {&a, &ref}) {
    if (img->ok()) continue;
    std::fprintf(stderr, "raylane: %s\n", img->error().c_str());
    return kExitUsage;
  }
  auto d = compare(*a, *ref);
  if (!d) {
    std::fprintf(stderr, "raylane: %s\n", d.error().c_str());
    return kExitUsage;
  }
  std::printf("rmse %.6g relmse %.6g mean_abs %.6g max_abs %.6g max_x %u max_y %u max_channel %d\n",
              d->rmse, d->rel_mse, d->mean_abs, d->max_abs, d->max_x, d->max_y, d->max_channel);
  if (heatmap) {
    if (Status s = write_image(*heatmap, relative_error_map(*a, *ref)); !s) {
      std::fprintf(stderr, "raylane: cannot write %s: %s\n", heatmap->c_str(), s.error().c_str());
      return kExitFailure;
    }
    std::printf("%s\n", heatmap->c_str());
  }
  if (d->nonfinite > 0) {
    std::printf("%s %s NaN or infinite (in %s or %s): the images differ beyond any --tol\n",
                counted(d->nonfinite, "channel value").c_str(), d->nonfinite == 1 ? "is" : "are",
                a_path.c_str(), ref_path.c_str());
    return kExitFailure;
  }
  return d->rmse > tol ? kExitFailure : kExitOk;
}

}  // namespace raylane::cli
