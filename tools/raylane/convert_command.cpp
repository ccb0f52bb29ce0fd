// `raylane convert IN OUT [--exposure E] [--half]`: any image raylane writes (HDR, PFM, EXR)
// or reads as a texture (PNG, JPEG, TGA, BMP) into one of the formats it writes, chosen by OUT's
// extension (the course's users viewed HDR files this way).
#include <cstdio>

#include "aov_outputs.h"
#include "args.h"
#include "commands.h"
#include "exr_extras.h"
#include "file_roles.h"
#include "image_reading.h"
#include "raylane/image/write_image.h"

namespace raylane::cli {

namespace {
const std::vector<OptionSpec> kConvertOptions = {
    {"exposure", 0, "E", false, "PNG exposure in stops (pixel · 2^E)", "0"},
    {"half", 0, "", false, "EXR: 16-bit half channels instead of 32-bit float", ""},
    {"image-memory", 0, "MIB", false, kImageMemoryHelp, kImageMemoryDefault},
};
const CommandHelp kConvertHelp{
    "raylane convert IN OUT [--exposure E] [--half] [--image-memory MIB]",
    "Writes the image IN (.hdr, .pfm, .exr, or .png, .jpg, .tga, .bmp read as linear RGB) as\n"
    "OUT, in the format OUT's extension names: .hdr, .pfm, .png (8-bit sRGB) or .exr (RGB,\n"
    "float or --half). From .exr to .exr, the layers (render's --aov: albedo.R, ...) and the\n"
    "header's string attributes (RAYLANE_SPP, ...) are kept too.",
    &kConvertOptions, ""};
}  // namespace

int convert_command(const std::vector<std::string>& args) {
  if (asks_for_help(args, kConvertOptions)) return print_help(kConvertHelp);
  auto parsed = parse_args(args, kConvertOptions);
  if (!parsed) return usage_error("convert", parsed.error());
  if (parsed->positional.size() != 2) return usage_error("convert", "convert takes IN and OUT");
  const std::string& in = parsed->positional[0];
  const std::string& out = parsed->positional[1];
  WriteOptions opts;
  if (auto e = parsed->last("exposure")) {
    auto v = parse_double_option("exposure", *e);
    if (!v) return usage_error("convert", v.error());
    opts.exposure = *v;
  }
  opts.exr_half = parsed->has("half");
  ImageMemoryOption memory;
  if (auto v = parsed->last("image-memory"))
    if (Status s = read_image_memory_option(*v, memory.bytes, memory.chosen); !s)
      return usage_error("convert", s.error());
  auto format = format_from_path(out);
  if (!format) return usage_error("convert", format.error());
  if (opts.exr_half && *format != ImageFormat::kExr)
    std::fprintf(stderr, "raylane: warning: --half does nothing unless OUT is an .exr file\n");
  if (parsed->has("exposure") && *format != ImageFormat::kPng)
    std::fprintf(stderr, "raylane: warning: --exposure does nothing unless OUT is a .png file\n");
  if (Status s = check_outputs_apart({{in, "the input image"}}, {{out, "the output"}}); !s)
    return usage_error("convert", s.error());
  auto header = read_any_header(in);
  if (!header) {
    std::fprintf(stderr, "raylane: %s\n", header.error().c_str());
    return kExitUsage;
  }
  if (Status s = check_images_memory({*header}, 0, memory); !s) {
    // The decoding-ratio rule's message names the file already.
    const bool named = s.error().rfind(in + ":", 0) == 0;
    std::fprintf(stderr, "raylane: %s%s%s\n", named ? "" : in.c_str(), named ? "" : ": ",
                 s.error().c_str());
    return kExitUsage;
  }
  auto image = read_any_image(*header);
  if (!image) {
    std::fprintf(stderr, "raylane: %s\n", image.error().c_str());
    return kExitUsage;
  }
  if (*format == ImageFormat::kExr && is_exr(in)) {
    auto extras = read_exr_extras(in);
    if (!extras) {
      std::fprintf(stderr, "raylane: %s\n", extras.error().c_str());
      return kExitUsage;
    }
    for (const std::string& what : extras->not_kept)
      std::fprintf(stderr, "raylane: warning: %s: %s is not kept\n", in.c_str(), what.c_str());
    opts.exr_layers = std::move(extras->layers);
    opts.metadata = std::move(extras->metadata);
  }
  if (Status s = write_image(out, *image, opts); !s) {
    std::fprintf(stderr, "raylane: cannot write %s: %s\n", out.c_str(), s.error().c_str());
    return kExitFailure;
  }
  std::printf("%s\n", out.c_str());
  return kExitOk;
}

}  // namespace raylane::cli
