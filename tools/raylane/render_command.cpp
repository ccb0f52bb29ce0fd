// `raylane render`: read the options (render_options.cpp), load the scene, check the outputs,
// render, write.
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "aov_outputs.h"
#include "args.h"
#include "checkpoint.h"
#include "cluster.h"
#include "commands.h"
#include "file_roles.h"
#include "pass_series.h"
#include "progress.h"
#include "raylane/core/strings.h"
#include "raylane/image/write_image.h"
#include "raylane/render/path.h"
#include "raylane/render/raycast.h"
#include "region_option.h"
#include "render_request.h"
#include "stats_json.h"

namespace raylane::cli {

namespace {

// No output may be an input (the scene file, a mesh or a file it names, the --resume film)
// or another output. A --checkpoint that is the --resume film is allowed: the film is read
// whole first and saved again with more passes, the way a long render is continued.
// `passes`: the count the final images are named by ({pass}), --spp before rendering.
Status outputs_apart_from_inputs(const RenderRequest& r, const std::vector<std::string>& read,
                                 int passes) {
  std::vector<FileRole> inputs, outputs;
  for (std::size_t i = 0; i < read.size(); ++i)
    inputs.push_back(
        {read[i], i == 0 && r.scene_path ? "the scene file" : "a file the scene reads"});
  const auto& c = r.checkpoints;
  if (c.resume && !(c.checkpoint && same_file(*c.checkpoint, *c.resume)))
    inputs.push_back({*c.resume, "the --resume film"});
  for (const std::string& out : final_outputs(r, passes))
    outputs.push_back({out, "the output"});
  for (const auto& [out, aov] : aov_siblings(final_outputs(r, passes), r.path_settings.aovs))
    outputs.push_back({out, "an --aov output"});
  for (const std::string& out : series_outputs(r))
    outputs.push_back({out, "a --save-at output"});
  if (c.checkpoint) outputs.push_back({*c.checkpoint, "the --checkpoint film"});
  if (r.stats_json) outputs.push_back({*r.stats_json, "the --stats-json file"});
  return check_outputs_apart(inputs, outputs);
}

// A --checkpoint film that exists holds samples, maybe hours of them: only --resume of that
// same film may write over it (it is read whole first and saved with more passes).
Status checkpoint_keeps_samples(const CheckpointOptions& c) {
  if (!c.checkpoint) return ok_status();
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(*c.checkpoint, ec)))
    return ok_status();
  if (c.resume && same_file(*c.checkpoint, *c.resume)) return ok_status();
  return Error{cat("--checkpoint ", *c.checkpoint,
                   " already exists and would be replaced at the first checkpoint; continue it "
                   "with --resume ",
                   *c.checkpoint, ", or remove it")};
}

// Every output is checked before rendering starts, so a long render is never lost to a typo.
bool outputs_writable(const RenderRequest& r) {
  bool ok = true;
  std::vector<std::string> all = final_outputs(r, r.path_settings.spp);
  for (const auto& [out, aov] : r.aov_outputs)
    all.push_back(out);
  if (r.stats_json) all.push_back(*r.stats_json);
  for (const std::string& out : series_outputs(r))
    all.push_back(out);
  for (const auto& out : all) {
    if (Status s = check_writable(out); !s) {
      std::fprintf(stderr, "raylane: cannot write %s: %s\n", out.c_str(), s.error().c_str());
      ok = false;
    }
  }
  return ok;
}

// Files that could not be written lose nothing: the film is saved beside them, and the user
// is told how to write the images from it without rendering again.
void keep_film(const RenderRequest& r, const Scene& scene, Film& film) {
  auto kept = save_rescue_film(film, scene, r.path_settings, r.outputs.front());
  if (!kept) {
    std::fprintf(stderr, "raylane: %s\n", kept.error().c_str());
    return;
  }
  const auto& region = r.path_settings.region;
  std::fprintf(stderr,
               "raylane: the render's film is kept as %s: this run's options with `--resume %s "
               "--spp %d%s` write its images again without rendering\n",
               kept->c_str(), quote_path(*kept).c_str(), film.passes,
               region ? cat(" --region ", region_text(*region)).c_str() : "");
}

// A path render's images. A render stopped before --spp (--time, Ctrl-C) names a {pass}
// output by the passes it holds, a name the checks before rendering did not see: it is checked
// now, and where it would overwrite an input or another output the film is kept instead.
std::vector<std::string> write_final_images(const RenderRequest& r,
                                            const std::vector<std::string>& inputs,
                                            const Film& film, const WriteOptions& wopts,
                                            bool& failed) {
  if (film.passes != r.path_settings.spp) {
    RenderRequest late = r;
    late.save_at.clear();  // written already; the checkpoint and --stats-json were checked
    late.checkpoints = {};
    late.stats_json.reset();
    if (Status s = outputs_apart_from_inputs(late, inputs, film.passes); !s) {
      std::fprintf(stderr, "raylane: cannot write the images after %d passes: %s\n", film.passes,
                   s.error().c_str());
      failed = true;
      return {};
    }
  }
  return write_film_outputs(final_outputs(r, film.passes), film, wopts, failed);
}

// Under mpirun only rank 0 speaks: the others' messages would repeat its own (every process
// reads the same scene and options), so their stdout and stderr go to /dev/null. If that
// cannot be opened, the messages repeat; nothing else changes.
void silence_unless_root(const Cluster& cluster) {
  if (cluster.root()) return;
  if (std::freopen("/dev/null", "w", stdout) == nullptr) return;
  if (std::freopen("/dev/null", "w", stderr) == nullptr) return;
}

}  // namespace

int render_command(const std::vector<std::string>& args) {
  if (asks_for_help(args, render_specs())) return print_help(render_help());
  Cluster cluster;
  silence_unless_root(cluster);
  auto request = read_render_request(args);
  if (!request) return usage_error("render", request.error());
  const RenderRequest& r = *request;
  if (!r.quiet)
    for (const std::string& w : r.warnings)
      std::fprintf(stderr, "raylane: warning: %s\n", w.c_str());
  auto parsed = load_scene_for_cli(r.scene_path, r.lenient, r.quiet, r.overrides,
                                   {r.image_memory, false, r.image_memory_chosen});
  if (int bad = cluster.first_failure(parsed.has_value()); bad >= 0) {
    if (bad > 0) std::fprintf(stderr, "raylane: rank %d cannot load the scene\n", bad);
    return kExitUsage;
  }
  if (Status s = outputs_apart_from_inputs(r, parsed->input_files, r.path_settings.spp); !s)
    return usage_error("render", s.error());
  if (Status s = checkpoint_keeps_samples(r.checkpoints); r.path && !s)
    return usage_error("render", s.error());
  if (Status s = region_fits(r.path_settings.region, parsed->scene); !s)
    return usage_error("render", s.error());
  if (Status s = render_fits_in_memory(r, parsed->scene, cluster.distributed()); !s) {
    std::fprintf(stderr, "raylane: %s; nothing rendered\n", s.error().c_str());
    return kExitUsage;
  }
  Scene* scene = &parsed->scene;
  if (cluster.first_failure(!cluster.root() || outputs_writable(r)) >= 0) return kExitUsage;
  if (!r.path && !cluster.root()) return kExitOk;  // a ray-casting view: rank 0 alone
  if (r.threads > 0) omp_set_num_threads(r.threads);

  // The BVH is built for every tracer: it permutes the tables, so all tracers name the same
  // primitive by the same row (and `--mode id` images compare across tracers).
  Bvh bvh = build_bvh_and_reorder(*scene, render_bvh_config(*scene));
  Tracer tracer(*scene, bvh, r.tracer, r.isa);
  const SdfMarchCounts marches_before = sdf_march_counts();  // --stats: this render's marches
  auto start = std::chrono::steady_clock::now();
  uint64_t rays = 0;
  std::string what;
  Image image;  // a ray-casting view's
  Film film;    // a path render's: its files are written from it
  int spp = 1;
  PathStats path_stats;
  PathOutcome balance;  // the MPI job's wait and tile moves (--stats), the --save-at series
  bool interrupted_run = false, series_failed = false;
  if (r.path) {
    PathOutcome run = run_path(r, tracer, cluster);
    if (run.status != kExitOk) return run.status;
    if (!cluster.root()) return cluster.root_status(kExitOk);
    film = std::move(run.film);
    path_stats = run.stats;
    balance.wait_seconds = run.wait_seconds, balance.busy_seconds = run.busy_seconds;
    balance.tiles_moved = run.tiles_moved, balance.balances = run.balances;
    interrupted_run = run.interrupted;
    series_failed = run.series_failed;
    balance.series = std::move(run.series);
    rays = path_stats.rays();
    spp = path_stats.passes;
    what = cat("path/", integrator_name(r.path_settings.integrator), "/",
               sampler_name(r.path_settings.sampler), "/", shading_name(r.path_settings.shading),
               ", ", path_stats.passes, " spp", run.interrupted ? ", interrupted" : "",
               cluster.distributed() ? cat(", ", cluster.size(), " processes") : "");
  } else {
    RaycastStats stats;
    const auto& region = r.path_settings.region;
    image = render_raycast(tracer, r.mode, &stats, region);  // the region's size
    rays = stats.camera_rays + stats.shadow_rays;
    path_stats.camera_rays = stats.camera_rays, path_stats.shadow_rays = stats.shadow_rays;
    what = std::string(raycast_mode_name(r.mode));
  }
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  WriteOptions wopts;
  wopts.exposure = r.exposure;
  wopts.exr_half = r.exr_half;
  wopts.metadata.push_back(
      cat("RAYLANE_MODE=", r.path ? std::string_view("path") : raycast_mode_name(r.mode)));
  wopts.metadata.push_back(cat("RAYLANE_SPP=", spp));
  if (r.path)
    for (std::string& line : path_metadata(r.path_settings))
      wopts.metadata.push_back(std::move(line));
  if (const auto& region = r.path_settings.region)
    wopts.metadata.push_back(cat("RAYLANE_REGION=", region_text(*region)));
  int status = kExitOk;
  // A render is never dropped: an output that fails now (the folder was removed, the disk
  // filled up) goes to a rescue file instead, whose path is printed; the status says so.
  bool failed = series_failed;
  std::vector<std::string> written;  // for --stats-json
  if (r.path) {
    written = write_final_images(r, parsed->input_files, film, wopts, failed);
  } else {
    // 8-bit files get depth and id mapped for viewing; HDR and PFM keep the raw values.
    const Image view = viewable(image, r.mode);
    for (const auto& out : r.outputs) {
      bool eight_bit = format_from_path(out).ok() && *format_from_path(out) == ImageFormat::kPng;
      if (auto path = write_render_output(out, eight_bit ? view : image, wopts, failed))
        written.push_back(*path);
    }
  }
  if (failed) status = kExitFailure;
  if (failed && r.path) keep_film(r, *scene, film);
  const PixelRegion shown = r.path ? film.window() : PixelRegion{0, 0, image.width, image.height};
  if (!r.quiet) {
    std::fprintf(stderr,
                 "rendered %ux%u%s (%s) in %.3f s: %s, %.2f Mrays/s; %s tracer, %s, %s; BVH of "
                 "%s built in %.3f s\n",
                 shown.width(), shown.height(),
                 shown.width() == scene->width && shown.height() == scene->height
                     ? ""
                     : cat(" of ", scene->width, "x", scene->height).c_str(),
                 what.c_str(), seconds, counted(rays, "ray").c_str(), rays / seconds * 1e-6,
                 std::string(tracer_backend_name(r.tracer)).c_str(),
                 std::string(isa_name(r.isa)).c_str(),
                 counted(omp_get_max_threads(), "thread").c_str(),
                 counted(bvh.nodes.size(), "node").c_str(), bvh.stats.build_seconds);
  }
  if (r.stats_json &&
      !write_summary_json(*r.stats_json,
                          render_summary(r, *scene, bvh, path_stats, balance, seconds,
                                         interrupted_run, cluster.size(), std::move(written))))
    status = kExitFailure;
  if (r.path && r.print_phases && !r.quiet) {
    print_phases(path_stats, seconds, omp_get_max_threads() * cluster.size());
    if (cluster.distributed()) print_balance(balance, cluster.size());
  }
  if (r.print_phases && !r.quiet && scene->table<Sdf>().size() > 0) {
    // The float march's counts (sdf_packet.h; this process's threads alone under mpirun).
    SdfMarchCounts m = sdf_march_counts();
    uint64_t marches = m.marches - marches_before.marches, steps = m.steps - marches_before.steps;
    std::fprintf(stderr,
                 "sdf blocks: %llu marches, %.2f steps per march, %llu out of steps (misses)\n",
                 (unsigned long long)marches, marches ? double(steps) / double(marches) : 0.0,
                 (unsigned long long)(m.out_of_steps - marches_before.out_of_steps));
  }
  if (status == kExitOk && interrupted_run) status = kExitInterrupted;
  return r.path ? cluster.root_status(status) : status;
}

}  // namespace raylane::cli
