// `raylane render`: parse options, load the scene, check the outputs, render, write.
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "args.h"
#include "checkpoint.h"
#include "commands.h"
#include "progress.h"
#include "raylane/core/strings.h"
#include "raylane/image/write_fallback.h"
#include "raylane/image/write_image.h"
#include "raylane/render/path.h"
#include "raylane/render/raycast.h"

namespace raylane::cli {

namespace {

struct RenderRequest {
  std::optional<std::string> scene_path;
  std::vector<std::string> outputs;
  bool path = true;  // --mode path (the default); otherwise a ray-casting mode
  RaycastMode mode = RaycastMode::kLit;
  PathSettings path_settings;
  CheckpointOptions checkpoints;
  TracerKind tracer = TracerKind::kPacket;
  Isa isa = best_isa();
  TraversalPolicy traversal = TraversalPolicy::kPackets;
  double exposure = 0;
  int threads = 0;
  bool lenient = false, quiet = false;
};

constexpr int kExitInterrupted = 130;  // 128 + SIGINT, as shells report it

const std::vector<OptionSpec> kRenderOptions = {
    {"output", 'o', true, true},   {"mode", 0, true, false},
    {"exposure", 0, true, false},  {"threads", 0, true, false},
    {"lenient", 0, false, false},  {"quiet", 'q', false, false},
    {"tracer", 0, true, false},    {"isa", 0, true, false},
    {"traversal", 0, true, false}, {"spp", 0, true, false},
    {"seed", 0, true, false},      {"integrator", 0, true, false},
    {"max-depth", 0, true, false}, {"time", 0, true, false},
    {"png", 0, false, false},      {"checkpoint", 0, true, false},
    {"resume", 0, true, false},    {"checkpoint-every", 0, true, false},
};

std::string default_output(const std::optional<std::string>& scene_path) {
  std::string stem = scene_path ? std::filesystem::path(*scene_path).stem().string() : "testscene";
  return stem + ".hdr";
}

Status read_path_settings(const ParsedArgs& parsed, PathSettings& p) {
  if (auto v = parsed.last("integrator")) {
    auto i = integrator_from_name(*v);
    if (!i) return Error{cat("unknown --integrator ", in_quotes(*v), " (brdf, nee, mis)")};
    p.integrator = *i;
  }
  if (auto v = parsed.last("spp")) {
    auto n = parse_int_option("spp", *v, 1, 1 << 24);
    if (!n) return Error{n.error()};
    p.spp = int(*n);
  }
  if (auto v = parsed.last("seed")) {
    auto n = parse_int_option("seed", *v, 0, std::numeric_limits<long>::max());
    if (!n) return Error{n.error()};
    p.seed = uint64_t(*n);
  }
  if (auto v = parsed.last("max-depth")) {
    auto n = parse_int_option("max-depth", *v, 0, 1 << 16);
    if (!n) return Error{n.error()};
    p.max_depth = int(*n);
  }
  if (auto v = parsed.last("time")) {
    auto t = parse_double_option("time", *v);
    if (!t) return Error{t.error()};
    if (!(*t > 0)) return Error{cat("--time takes a number of seconds > 0, found ", *v)};
    p.time_limit = *t;
  }
  return ok_status();
}

Result<RenderRequest> read_request(const std::vector<std::string>& args) {
  auto parsed = parse_args(args, kRenderOptions);
  if (!parsed) return Error{parsed.error()};
  RenderRequest r;
  if (parsed->positional.size() > 1) return Error{"render takes at most one scene file"};
  if (!parsed->positional.empty()) r.scene_path = parsed->positional[0];
  if (auto m = parsed->last("mode"); m && *m != "path") {
    auto mode = raycast_mode_from_name(*m);
    if (!mode)
      return Error{
          cat("unknown --mode ", in_quotes(*m), " (path, normal, depth, albedo, id, lit)")};
    r.mode = *mode;
    r.path = false;
  }
  if (Status s = read_path_settings(*parsed, r.path_settings); !s) return Error{s.error()};
  if (Status s = read_checkpoint_options(*parsed, r.checkpoints); !s) return Error{s.error()};
  if (auto t = parsed->last("tracer")) {
    auto kind = tracer_kind_from_name(*t);
    if (!kind) return Error{cat("unknown --tracer ", in_quotes(*t), " (packet, bvh, scalar)")};
    r.tracer = *kind;
  }
  if (auto t = parsed->last("traversal")) {
    auto policy = traversal_policy_from_name(*t);
    if (!policy) return Error{cat("unknown --traversal ", in_quotes(*t), " (packets, rays, auto)")};
    r.traversal = *policy;
  }
  if (auto i = parsed->last("isa")) {
    auto isa = parse_isa_option(*i);
    if (!isa) return Error{isa.error()};
    r.isa = *isa;
  }
  if (auto e = parsed->last("exposure")) {
    auto v = parse_double_option("exposure", *e);
    if (!v) return Error{v.error()};
    r.exposure = *v;
  }
  if (auto t = parsed->last("threads")) {
    auto v = parse_int_option("threads", *t, 0, 4096);
    if (!v) return Error{v.error()};
    r.threads = int(*v);
  }
  r.lenient = parsed->has("lenient");
  r.quiet = parsed->has("quiet");
  if (parsed->has("output")) r.outputs = parsed->values.at("output");
  if (r.outputs.empty()) r.outputs.push_back(default_output(r.scene_path));
  bool has_png = false;
  for (const auto& out : r.outputs)
    has_png |= format_from_path(out).ok() && *format_from_path(out) == ImageFormat::kPng;
  if (parsed->has("png") && !has_png)
    r.outputs.push_back(std::filesystem::path(r.outputs[0]).replace_extension(".png").string());
  for (const auto& out : r.outputs)
    if (auto f = format_from_path(out); !f) return Error{f.error()};
  return r;
}

// Every output is checked before rendering starts, so a long render is never lost to a typo.
bool outputs_writable(const RenderRequest& r) {
  bool ok = true;
  for (const auto& out : r.outputs) {
    if (Status s = check_writable(out); !s) {
      std::fprintf(stderr, "raylane: cannot write %s: %s\n", out.c_str(), s.error().c_str());
      ok = false;
    }
  }
  return ok;
}

}  // namespace

int render_command(const std::vector<std::string>& args) {
  auto request = read_request(args);
  if (!request) return usage_error(request.error());
  const RenderRequest& r = *request;
  auto scene = load_scene_for_cli(r.scene_path, r.lenient, r.quiet);
  if (!scene) return kExitUsage;
  if (!outputs_writable(r)) return kExitUsage;
  if (r.threads > 0) omp_set_num_threads(r.threads);

  // The BVH is built for every tracer: it permutes the tables, so all tracers name the same
  // primitive by the same row (and `--mode id` images compare across tracers).
  Bvh bvh = build_bvh(*scene, {.wide_nodes = r.traversal != TraversalPolicy::kPackets});
  Tracer tracer(*scene, bvh, r.tracer, r.isa, r.traversal);
  auto start = std::chrono::steady_clock::now();
  uint64_t rays = 0;
  std::string what;
  Image image;
  int spp = 1;
  if (r.path) {
    auto film = starting_film(r.checkpoints, *scene, r.path_settings);
    if (!film) return std::fprintf(stderr, "raylane: %s\n", film.error().c_str()), kExitUsage;
    PathStats stats;
    Progress progress(r.path_settings.spp, r.path_settings.time_limit, r.quiet);
    Checkpointer checkpointer(r.checkpoints);
    PathSettings settings = r.path_settings;
    settings.stop = interrupt_flag();
    settings.on_pass = [&](int done) {
      progress.update(done);
      checkpointer.after_pass(*film);
    };
    install_interrupt_handler();
    image = render_path(tracer, settings, &stats, &*film);
    checkpointer.after_pass(*film, /*final=*/true);
    progress.finish();
    rays = stats.rays();
    spp = stats.passes;
    what = cat("path/", integrator_name(r.path_settings.integrator), ", ", stats.passes, " spp",
               interrupted() ? ", interrupted" : "");
  } else {
    RaycastStats stats;
    image = render_raycast(tracer, r.mode, &stats);
    rays = stats.camera_rays + stats.shadow_rays;
    what = std::string(raycast_mode_name(r.mode));
  }
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  WriteOptions wopts;
  wopts.exposure = r.exposure;
  wopts.metadata.push_back(
      cat("RAYLANE_MODE=", r.path ? std::string_view("path") : raycast_mode_name(r.mode)));
  wopts.metadata.push_back(cat("RAYLANE_SPP=", spp));
  int status = kExitOk;
  // A render is never dropped: an output that fails now (the folder was removed, the disk
  // filled up) goes to a rescue file instead, whose path is printed; the status says so.
  for (const auto& out : r.outputs) {
    auto saved = write_image_or_fallback(out, image, wopts);
    if (!saved) {
      std::fprintf(stderr, "raylane: cannot write %s: %s\n", out.c_str(), saved.error().c_str());
      status = kExitFailure;
      continue;
    }
    if (saved->is_fallback) {
      std::fprintf(stderr, "raylane: cannot write %s: %s; the image is saved as %s\n", out.c_str(),
                   saved->first_error.c_str(), saved->path.c_str());
      status = kExitFailure;
    }
    std::printf("%s\n", saved->path.c_str());
  }
  if (!r.quiet) {
    std::fprintf(stderr,
                 "rendered %ux%u (%s) in %.3f s: %llu rays, %.2f Mrays/s; %s tracer, %s, %s, %d "
                 "threads; BVH of %zu nodes built in %.3f s\n",
                 scene->width, scene->height, what.c_str(), seconds, (unsigned long long)rays,
                 rays / seconds * 1e-6, std::string(tracer_kind_name(r.tracer)).c_str(),
                 std::string(isa_name(r.isa)).c_str(),
                 std::string(traversal_policy_name(r.traversal)).c_str(), omp_get_max_threads(),
                 bvh.nodes.size(), bvh.stats.build_seconds);
  }
  if (status == kExitOk && r.path && interrupted()) return kExitInterrupted;
  return status;
}

}  // namespace raylane::cli
