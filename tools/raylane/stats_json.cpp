#include "stats_json.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "json_text.h"
#include "raylane/core/atomic_file.h"
#include "raylane/core/strings.h"
#include "raylane/render/raycast.h"

namespace raylane::cli {

namespace {

std::string phases_json(const RenderSummary& s) {
  const PathPhases& p = s.stats.phases;
  double available = s.seconds * s.threads * s.processes;
  return JsonObject()
      .number("camera_rays", p.camera)
      .number("tracing_camera_rays", p.trace_camera)
      .number("tracing_bounce_and_shadow_rays", p.trace_rest)
      .number("shading", p.shade)
      .number("light_sampling", p.lights)
      .number("film", p.film)
      .number("idle_and_other", std::max(0.0, available - p.total()))
      .number("thread_seconds", available)
      .str();
}

// [{"spp": N, "seconds": ..., "cpu_seconds": ..., "outputs": [...]}, ...]
std::string series_json(const std::vector<SeriesSave>& series) {
  std::string out = "[";
  for (std::size_t i = 0; i < series.size(); ++i)
    out += cat(i ? ", " : "", JsonObject()
                                  .count("spp", uint64_t(series[i].spp))
                                  .number("seconds", series[i].seconds)
                                  .number("cpu_seconds", series[i].cpu_seconds)
                                  .raw("outputs", json_string_array(series[i].outputs))
                                  .str());
  return out + "]";
}

}  // namespace

std::string summary_json(const RenderSummary& s) {
  const PathStats& st = s.stats;
  JsonObject o;
  o.count("width", s.width).count("height", s.height);
  if (!s.region.empty()) o.raw("region", s.region);
  o.string("mode", s.mode);
  if (s.mode == "path")
    o.string("integrator", s.integrator).string("sampler", s.sampler).string("shading", s.shading);
  o.count("spp", uint64_t(s.spp))
      .boolean("interrupted", s.interrupted)
      .number("seconds", s.seconds);
  o.raw("rays", JsonObject()
                    .count("camera", st.camera_rays)
                    .count("bounce", st.bounce_rays)
                    .count("shadow", st.shadow_rays)
                    .count("total", st.rays())
                    .str());
  o.number("mrays_per_second", s.seconds > 0 ? double(st.rays()) / s.seconds * 1e-6 : 0.0);
  if (s.mode == "path") o.count("nonfinite_samples", st.nonfinite_samples);
  o.raw("phases", s.phases_timed ? phases_json(s) : "null");
  o.string("tracer", s.tracer).string("isa", s.isa);
  o.count("threads", uint64_t(s.threads)).count("processes", uint64_t(s.processes));
  o.raw("bvh",
        JsonObject().count("nodes", s.bvh_nodes).number("build_seconds", s.bvh_seconds).str());
  if (s.processes > 1)
    o.raw("balance", JsonObject()
                         .number("wait_seconds", s.wait_seconds)
                         .number("busy_seconds", s.busy_seconds)
                         .count("tiles_moved", uint64_t(s.tiles_moved))
                         .count("balances", uint64_t(s.balances))
                         .str());
  if (s.path) o.raw("series", series_json(s.series));
  o.raw("outputs", json_string_array(s.outputs));
  return o.str() + "\n";
}

bool write_summary_json(const std::string& path, const RenderSummary& s) {
  Status written = write_file_atomically(path, summary_json(s));
  if (!written)
    std::fprintf(stderr, "raylane: cannot write %s: %s\n", path.c_str(), written.error().c_str());
  return written.ok();
}

RenderSummary render_summary(const RenderRequest& r, const Scene& scene, const Bvh& bvh,
                             const PathStats& stats, const PathOutcome& run, double seconds,
                             bool interrupted, int processes, std::vector<std::string> written) {
  RenderSummary s;
  s.width = scene.width, s.height = scene.height;
  if (const auto& g = r.path_settings.region)
    s.region = cat("[", g->x0, ", ", g->y0, ", ", g->x1, ", ", g->y1, "]");
  s.mode = r.path ? "path" : std::string(raycast_mode_name(r.mode));
  if (r.path) {
    const PathSettings& p = r.path_settings;
    s.integrator = integrator_name(p.integrator);
    s.sampler = sampler_name(p.sampler);
    s.shading = shading_name(p.shading);
  }
  s.spp = r.path ? stats.passes : 1;
  s.interrupted = interrupted;
  s.seconds = seconds;
  s.stats = stats;
  s.phases_timed = r.path && r.path_settings.time_phases;
  s.tracer = tracer_backend_name(r.tracer);
  s.isa = isa_name(r.isa);
  s.threads = omp_get_max_threads();
  s.processes = processes;
  s.bvh_nodes = bvh.nodes.size();
  s.bvh_seconds = bvh.stats.build_seconds;
  s.wait_seconds = run.wait_seconds, s.busy_seconds = run.busy_seconds;
  s.tiles_moved = run.tiles_moved, s.balances = run.balances;
  s.path = r.path;
  s.series = run.series;
  s.outputs = std::move(written);
  return s;
}

}  // namespace raylane::cli
