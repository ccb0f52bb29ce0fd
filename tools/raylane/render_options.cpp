// The options of `raylane render` (render_command.cpp): their table, their help, and the
// request they make (render_request.h).
#include <filesystem>
#include <functional>
#include <limits>

#include "aov_outputs.h"
#include "args.h"
#include "checkpoint.h"
#include "commands.h"
#include "pass_series.h"
#include "raylane/core/strings.h"
#include "raylane/image/write_image.h"
#include "raylane/render/path.h"
#include "raylane/render/raycast.h"
#include "region_option.h"
#include "render_request.h"

namespace raylane::cli {

namespace {

// Options that only the path tracer reads: given with a ray-casting view, they do nothing.
constexpr std::string_view kPathOnlyOptions[] = {
    "spp",       "integrator", "sampler",    "shading", "seed",
    "max-depth", "time",       "checkpoint", "resume",  "checkpoint-every",
    "stats",     "aov",        "balance",    "save-at", "no-checkpoint"};

// An option of `raylane render`: how it is written and described, and what it does to the
// request. Values are applied in the table's order, each option's values in the order given.
struct RenderOption {
  OptionSpec spec;
  std::function<Status(RenderRequest&, const std::string& value)> apply;
};

Status set_mode(RenderRequest& r, const std::string& v) {
  r.path = v == "path";
  if (r.path) return ok_status();
  auto mode = raycast_mode_from_name(v);
  if (!mode)
    return Error{cat("unknown --mode ", in_quotes(v), " (path, ", kRaycastModeNames.list(), ")")};
  r.mode = *mode;
  return ok_status();
}

Status set_integrator(RenderRequest& r, const std::string& v) {
  auto i = integrator_from_name(v);
  if (!i)
    return Error{cat("unknown --integrator ", in_quotes(v), " (", kIntegratorNames.list(), ")")};
  r.path_settings.integrator = *i;
  return ok_status();
}

Status set_sampler(RenderRequest& r, const std::string& v) {
  auto s = sampler_from_name(v);
  if (!s) return Error{cat("unknown --sampler ", in_quotes(v), " (", kSamplerNames.list(), ")")};
  r.path_settings.sampler = *s;
  return ok_status();
}

Status set_shading(RenderRequest& r, const std::string& v) {
  auto s = shading_from_name(v);
  if (!s) return Error{cat("unknown --shading ", in_quotes(v), " (", kShadingNames.list(), ")")};
  r.path_settings.shading = *s;
  return ok_status();
}

Status set_time(RenderRequest& r, const std::string& v) {
  double t = 0;
  if (Status s = read_double_option("time", v, t); !s) return s;
  if (!(t > 0)) return Error{cat("--time takes a number of seconds > 0, found ", v)};
  r.path_settings.time_limit = t;
  return ok_status();
}

Status set_checkpoint_every(RenderRequest& r, const std::string& v) {
  double t = 0;
  if (Status s = read_double_option("checkpoint-every", v, t); !s) return s;
  if (!(t >= 0)) return Error{cat("--checkpoint-every takes seconds ≥ 0, found ", v)};
  r.checkpoints.every = t;
  return ok_status();
}

Status set_tracer(RenderRequest& r, const std::string& v) {
  auto kind = tracer_backend_from_name(v);
  if (!kind)
    return Error{cat("unknown --tracer ", in_quotes(v), " (", kTracerBackendNames.list(), ")")};
  r.tracer = *kind;
  return ok_status();
}

Status set_balance(RenderRequest& r, const std::string& v) {
  auto b = kTileBalanceNames.from_name(v);
  if (!b)
    return Error{cat("unknown --balance ", in_quotes(v), " (", kTileBalanceNames.list(), ")")};
  r.balance = *b;
  return ok_status();
}

Status set_isa(RenderRequest& r, const std::string& v) {
  auto isa = parse_isa_option(v);
  if (!isa) return Error{isa.error()};
  r.isa = *isa;
  return ok_status();
}

const std::vector<RenderOption>& render_options() {
  using R = RenderRequest;
  using V = const std::string&;
  static const std::vector<RenderOption> options = {
      {{"output", 'o', "FILE", true,
        "image to write; the extension picks the format: .hdr (Radiance RGBE),\n"
        ".pfm (float), .png (8-bit sRGB), .exr (OpenEXR). Repeat to write several.",
        "<scene name>.hdr in the working directory"},
       [](R& r, V v) {
         r.outputs.push_back(v);
         return ok_status();
       }},
      {{"mode", 0, "MODE", false,
        cat("path, or a ray-casting view: ", kRaycastModeNames.list(),
            ".\n"
            "As PNG, depth runs from white (the nearest hit) to 10 % grey (the farthest),\n"
            "linear in t, misses black; ids become colours;\n"
            ".hdr and .pfm keep the raw values (t; kind tag + 1, row)"),
        "path"},
       set_mode},
      {{"spp", 0, "N", false, "path: samples per pixel, in progressive passes", "16"},
       [](R& r, V v) {
         r.spp_given = true;
         return read_int_option("spp", v, 1, kMaxSpp, r.path_settings.spp);
       }},
      {{"integrator", 0, "I", false,
        cat("path: ", kIntegratorNames.list(),
            ": BSDF sampling only; light sampling only;\n"
            "both, weighted by the power heuristic"),
        "mis"},
       set_integrator},
      {{"sampler", 0, "S", false,
        cat("path: ", kSamplerNames.list(),
            ": the course's MT19937-64; Owen-scrambled Sobol\n"
            "(less noise per sample; docs/design.md, \"Samplers\")"),
        "sobol"},
       set_sampler},
      {{"shading", 0, "S", false,
        cat("path: ", kShadingNames.list(),
            ": the double-precision BSDF one vertex at a time;\n"
            "a wavefront's vertices at once in float SIMD lanes (docs/design.md,\n"
            "\"Shading in lanes\")"),
        "float"},
       set_shading},
      {{"seed", 0, "S", false, "path: image seed; the image is the same for any --threads", "0"},
       [](R& r, V v) {
         return read_int_option("seed", v, 0, std::numeric_limits<long>::max(),
                                r.path_settings.seed);
       }},
      {{"max-depth", 0, "D", false, "path: at most D bounces (Russian roulette after 3)", "64"},
       [](R& r, V v) {
         return read_int_option("max-depth", v, 0, 1 << 16, r.path_settings.max_depth);
       }},
      {{"time", 0, "SECONDS", false,
        "path: a time budget: stop after the pass that ends past it. With --spp,\n"
        "whichever comes first; without, render until the budget is spent",
        "none"},
       set_time},
      {{"checkpoint", 0, "FILE", false,
        "path: save the film to FILE every --checkpoint-every seconds and\n"
        "when the render stops (done, --time, Ctrl-C, SIGTERM); a FILE that exists\n"
        "is refused unless it is the --resume film",
        "none"},
       [](R& r, V v) {
         r.checkpoints.checkpoint = v;
         return ok_status();
       }},
      {{"checkpoint-every", 0, "SECONDS", false, "path: seconds between checkpoints", "60"},
       set_checkpoint_every},
      {{"resume", 0, "FILE", false,
        "path: continue a saved film up to --spp; the same scene, --seed,\n"
        "--integrator and --max-depth give the uninterrupted run's image.\n"
        "Without --checkpoint, the run goes on saving into FILE",
        "none"},
       [](R& r, V v) {
         r.checkpoints.resume = v;
         return ok_status();
       }},
      {{"no-checkpoint", 0, "", false,
        "path: with --resume, leave the film as it is (save nothing)", ""},
       [](R& r, V) {
         r.no_checkpoint = true;
         return ok_status();
       }},
      {{"save-at", 0, "LIST", false,
        "path: also write the image after each listed pass (e.g. 1,4,16,64),\n"
        "as STEM.N.EXT beside each output: the file --spp N writes, bit for bit;\n"
        "an output named with {pass} (-o Image_Pass_{pass}.hdr) gets N there instead,\n"
        "and its final image the passes it holds (braces name nothing else)",
        "none"},
       set_save_at},
      {{"aov", 0, "LIST", false,
        cat("path: also sum ", kAovNames.list(),
            " of the first surface\n"
            "each sample meets (comma-separated), averaged like the colour;\n"
            "layers of an .exr output (albedo.R, normal.X, ...); beside any other\n"
            "output as STEM.albedo.pfm, STEM.normal.pfm, ..."),
        ""},
       [](R& r, V v) {
         auto set = parse_aov_list(v);
         if (!set) return Status{Error{set.error()}};
         r.path_settings.aovs = *set;
         return ok_status();
       }},
      {{"region", 0, "X0,Y0,X1,Y1", false, kRegionHelp, "the whole image"},
       [](R& r, V v) { return read_region_option(v, r.path_settings.region); }},
      {{"png", 0, "", false, "also write a PNG beside the first output", ""},
       [](R& r, V) {
         r.also_png = true;
         return ok_status();
       }},
      {{"exposure", 0, "E", false, "PNG exposure in stops (pixel · 2^E)", "0"},
       [](R& r, V v) { return read_double_option("exposure", v, r.exposure); }},
      {{"half", 0, "", false, "EXR: 16-bit half channels instead of 32-bit float", ""},
       [](R& r, V) {
         r.exr_half = true;
         return ok_status();
       }},
      {{"threads", 0, "N", false, "worker threads, 0 = all cores", "0"},
       [](R& r, V v) { return read_int_option("threads", v, 0, 4096, r.threads); }},
      {{"tracer", 0, "T", false,
        cat(kTracerBackendNames.list(),
            ": SIMD packets through the BVH; single rays\n"
            "through the BVH with the double kernels; brute force with the double kernels"),
        "packet"},
       set_tracer},
      {{"isa", 0, "I", false, cat(kIsaNames.list(), ", auto: the packet tracer's instruction set"),
        "auto, the widest this CPU has"},
       set_isa},
      {{"lenient", 0, "", false, "skip bad scene lines with a warning instead of failing", ""},
       [](R& r, V) {
         r.lenient = true;
         return ok_status();
       }},
      {{"image-memory", 0, "MIB", false, kImageMemoryHelp, kImageMemoryDefault},
       [](R& r, V v) {
         return read_image_memory_option(v, r.image_memory, r.image_memory_chosen);
       }},
      {{"set", 0, "LINE", true, kSetOptionHelp, ""},
       [](R& r, V v) {
         r.overrides.push_back(v);
         return ok_status();
       }},
      {{"balance", 0, "B", false,
        cat(kTileBalanceNames.list(),
            ": under mpirun, whether the processes deal their tiles again by\n"
            "measured cost after passes 2, 4, 8, ... (auto: when that evens them by 5 % or\n"
            "more); the image is the same either way"),
        "auto"},
       set_balance},
      {{"stats", 0, "", false,
        "path: at the end, where the time went (camera rays, tracing, shading, light\n"
        "sampling, film, idle) and the rays per second of each kind; any mode: the sdf\n"
        "blocks' mean steps per march and the marches that ran out of steps",
        ""},
       [](R& r, V) {
         r.path_settings.time_phases = r.print_phases = true;
         return ok_status();
       }},
      {{"stats-json", 0, "FILE", false,
        "write the summary (size, spp, seconds, rays by kind, Mrays/s, threads,\n"
        "processes, BVH, outputs) and the phases of --stats as one JSON object",
        "none"},
       [](R& r, V v) {
         r.stats_json = v;
         r.path_settings.time_phases = true;
         return ok_status();
       }},
      {{"quiet", 'q', "", false, "print only errors and the written image paths (no progress bar)",
        ""},
       [](R& r, V) {
         r.quiet = true;
         return ok_status();
       }},
  };
  return options;
}

std::string default_output(const std::optional<std::string>& scene_path) {
  std::string stem = scene_path ? std::filesystem::path(*scene_path).stem().string() : "testscene";
  return stem + ".hdr";
}

}  // namespace

const std::vector<OptionSpec>& render_specs() {
  static const std::vector<OptionSpec> specs = [] {
    std::vector<OptionSpec> out;
    for (const RenderOption& o : render_options())
      out.push_back(o.spec);
    return out;
  }();
  return specs;
}

const CommandHelp& render_help() {
  static const CommandHelp help{
      "raylane render [SCENE] [options]",
      "Renders SCENE (default: the built-in course test scene) by path tracing or one of the\n"
      "ray-casting views, and writes the image.",
      &render_specs(),
      "A path render shows a progress bar (on a terminal) and ends with a summary. The first\n"
      "Ctrl-C finishes the pass in flight and writes the image converged so far (RAYLANE_SPP in\n"
      "the HDR and EXR headers), exit status 130; a second Ctrl-C exits at once. SIGTERM\n"
      "(timeout, kill, batch schedulers) and SIGUSR1 do the same.\n"
      "The scene language: docs/scene-language.md."};
  return help;
}

Result<RenderRequest> read_render_request(const std::vector<std::string>& args) {
  auto parsed = parse_args(args, render_specs());
  if (!parsed) return Error{parsed.error()};
  RenderRequest r;
  if (parsed->positional.size() > 1) return Error{"render takes at most one scene file"};
  if (!parsed->positional.empty()) r.scene_path = parsed->positional[0];
  for (const RenderOption& o : render_options()) {
    auto given = parsed->values.find(o.spec.name);
    if (given == parsed->values.end()) continue;
    for (const std::string& value : given->second)
      if (Status s = o.apply(r, value); !s) return Error{s.error()};
  }
  if (r.no_checkpoint && r.checkpoints.checkpoint)
    return Error{"--no-checkpoint and --checkpoint ask for opposite things: give one"};
  // A resumed render keeps saving into the film it continues: interrupted, it loses nothing
  // of what it added.
  if (r.checkpoints.resume && !r.checkpoints.checkpoint && !r.no_checkpoint) {
    r.checkpoints.checkpoint = r.checkpoints.resume;
    if (Status s = check_writable(*r.checkpoints.resume); !s)
      return Error{cat("cannot write the --resume film ", *r.checkpoints.resume, " (", s.error(),
                       "): a resumed render saves into it; --no-checkpoint leaves it as it is, "
                       "--checkpoint FILE saves elsewhere")};
  }
  if (r.checkpoints.checkpoint) {
    if (Status s = check_writable(*r.checkpoints.checkpoint); !s)
      return Error{cat("cannot write --checkpoint ", *r.checkpoints.checkpoint, ": ", s.error())};
  }
  // A time budget without --spp: render until it is spent.
  if (r.path_settings.time_limit > 0 && !r.spp_given) r.path_settings.spp = kMaxSpp;
  if (Status s = check_save_at(r); !s) return Error{s.error()};
  if (!r.path)
    for (std::string_view name : kPathOnlyOptions)
      if (parsed->has(std::string(name)))
        r.warnings.push_back(cat("--", name, " does nothing in the ray-casting view --mode ",
                                 raycast_mode_name(r.mode), "; it is for --mode path"));
  if (r.outputs.empty()) r.outputs.push_back(default_output(r.scene_path));
  bool has_png = false;
  for (const auto& out : r.outputs)
    has_png |= format_from_path(out).ok() && *format_from_path(out) == ImageFormat::kPng;
  if (r.also_png && !has_png)
    r.outputs.push_back(std::filesystem::path(r.outputs[0]).replace_extension(".png").string());
  bool has_exr = false;
  for (const auto& out : r.outputs) {
    auto f = format_from_path(out);
    if (!f) return Error{f.error()};
    has_exr |= *f == ImageFormat::kExr;
  }
  if (r.exr_half && !has_exr)
    r.warnings.push_back("--half does nothing without an .exr output; it is for -o FILE.exr");
  if (parsed->has("exposure") && !has_png && !r.also_png)
    r.warnings.push_back(
        "--exposure does nothing without a .png output; it is for -o FILE.png or --png");
  if (Status s = check_pass_patterns(r); !s) return Error{s.error()};
  // The siblings of the images a render that runs to --spp writes (patterns filled in).
  if (r.path)
    r.aov_outputs = aov_siblings(final_outputs(r, r.path_settings.spp), r.path_settings.aovs);
  return r;
}

}  // namespace raylane::cli
