// `raylane diff IMAGE REFERENCE [--tol T]`: how far an image is from a reference — RMSE,
// relative MSE, mean and max absolute difference over all channels — and exit status 1 when
// the RMSE exceeds T (default 0: any difference), as pbrt's `imgtool diff` does for scripts.
#include <cstdio>

#include "args.h"
#include "commands.h"
#include "raylane/image/metrics.h"
#include "raylane/image/write_image.h"

namespace raylane::cli {

namespace {
const std::vector<OptionSpec> kDiffOptions = {
    {"tol", 0, "T", false, "the largest RMSE that still counts as equal (exit status 0)", "0"},
};
const CommandHelp kDiffHelp{
    "raylane diff IMAGE REFERENCE [--tol T]",
    "Prints how far IMAGE is from REFERENCE (.hdr, .pfm or .exr, the same size): RMSE, relative MSE\n"
    "(mean of (a−b)²/(b²+0.01)), mean and largest absolute difference over all channels. Exit\n"
    "status 1 when the RMSE is over T.",
    &kDiffOptions, ""};
}  // namespace

int diff_command(const std::vector<std::string>& args) {
  if (asks_for_help(args, kDiffOptions)) return print_help(kDiffHelp);
  auto parsed = parse_args(args, kDiffOptions);
  if (!parsed) return usage_error(parsed.error());
  if (parsed->positional.size() != 2) return usage_error("diff takes IMAGE and REFERENCE");
  double tol = 0;
  if (auto t = parsed->last("tol")) {
    if (Status s = read_double_option("tol", *t, tol); !s) return usage_error(s.error());
    if (!(tol >= 0)) return usage_error("--tol must be ≥ 0");
  }
  const std::string& a_path = parsed->positional[0];
  const std::string& ref_path = parsed->positional[1];
  auto a = read_image(a_path);
  auto ref = read_image(ref_path);
  for (const auto* img : {&a, &ref}) {
    if (img->ok()) continue;
    std::fprintf(stderr, "raylane: %s\n", img->error().c_str());
    return kExitUsage;
  }
  if (a->width != ref->width || a->height != ref->height) {
    std::fprintf(stderr, "raylane: %s is %ux%u and %s is %ux%u: images of different sizes\n",
                 a_path.c_str(), a->width, a->height, ref_path.c_str(), ref->width, ref->height);
    return kExitUsage;
  }
  auto d = compare(*a, *ref);
  if (!d) {
    std::fprintf(stderr, "raylane: %s\n", d.error().c_str());
    return kExitUsage;
  }
  std::printf("rmse %.6g relmse %.6g mean_abs %.6g max_abs %.6g\n", d->rmse, d->rel_mse,
              d->mean_abs, d->max_abs);
  if (d->nonfinite > 0) {
    std::printf(
        "%llu channel values are NaN or infinite (in %s or %s): the images differ "
        "beyond any --tol\n",
        (unsigned long long)d->nonfinite, a_path.c_str(), ref_path.c_str());
    return kExitFailure;
  }
  return d->rmse > tol ? kExitFailure : kExitOk;
}

}  // namespace raylane::cli
