// Whole path-traced renders, timed (docs/benchmarks.md, "Render timings"): samples per second —
// pixels × passes over wall time — of the course scene, its glass and mirror variants, the course
// scene with the Stanford bunny on its table (tools/make_bunny writes the mesh) and a large mesh
// (the benchmark's 1.31M-triangle displaced icosphere, glossy, under a sphere light), per
// integrator, on 1 and all threads, with the BVH `raylane render` builds (render_bvh_config).
// One pass at the scene's own resolution per iteration, each with its own seed, so every
// iteration does the same kind of work. The `/phases` rows time the render's phases as
// `--stats` does and report the bounce and shadow rays' rate over their tracing time, to set
// beside bench_trace's rates for the same scene's diffuse and shadow rays.
//
//   build/bench/bench_render [--benchmark_filter=...] [--benchmark_repetitions=5 ...]
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

#include "icosphere.h"
#include "raylane/bvh/bvh.h"
#include "raylane/render/path.h"
#include "raylane/scene/parser.h"

namespace raylane::bench {
namespace {

struct RenderScene {
  ParsedScene parsed;
  Bvh bvh;
};

// bench/scenes/icosphere.scn with the mesh made in memory (the file needs an export first).
ParsedScene icosphere_scene() {
  ParsedScene p = parse_scene(
      "screen 320 240\ncamera 0 -4 0 0.5 x 90\nlight 30 30 30\nsphere -3 -4 4 0.5\n"
      "brdf 0.7 0.7 0.7 0.2 0.2 0.2 50\n",
      "icosphere.scn");
  if (p.ok())
    add_displaced_icosphere(p.scene.table<Triangle>(), 8, uint32_t(p.scene.materials.size() - 1));
  return p;
}

// The course scene with the bunny on the table: the line the scene file leaves commented out,
// with the mesh `tools/make_bunny --scan-units build/bench-data/bunny-scan.ply` writes (the
// bunny in the Stanford scan's units, which that line expects).
ParsedScene bunny_scene() {
  const std::string scenes = std::string(RAYLANE_SOURCE_DIR) + "/scenes/";
  std::string text = "mesh \"" + std::string(RAYLANE_BENCH_DATA) +
                     "/bunny-scan.ply\" -0.5 0.8 0.23 5.0 z -90 q 0 0 0.707107 0.707106";
  ParseOptions options;
  options.overrides.push_back(text);
  return load_scene_file(scenes + "testscene.scn", options);
}

// The course scene (built in), the icosphere or scenes/<name>.scn, loaded and built once.
const RenderScene* render_scene(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<RenderScene>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[name];
  if (!slot) {
    auto s = std::make_unique<RenderScene>();
    if (name == "testscene")
      s->parsed = load_builtin_scene();
    else if (name == "icosphere")
      s->parsed = icosphere_scene();
    else if (name == "testscene-bunny")
      s->parsed = bunny_scene();
    else
      s->parsed = load_scene_file(std::string(RAYLANE_SOURCE_DIR) + "/scenes/" + name + ".scn");
    if (!s->parsed.ok()) return nullptr;
    s->bvh = build_bvh_and_reorder(s->parsed.scene, render_bvh_config(s->parsed.scene));
    slot = std::move(s);
  }
  return slot.get();
}

void render_passes(benchmark::State& state, const std::string& name, Integrator integrator,
                   int threads, bool phases) {
  const RenderScene* s = render_scene(name);
  if (!s)
    return state.SkipWithError(
        ("cannot load scene " + name +
         (name == "testscene-bunny"
              ? " (run tools/make_bunny --scan-units build/bench-data/bunny-scan.ply first)"
              : ""))
            .c_str());
  omp_set_num_threads(threads);
  Tracer tracer(s->parsed.scene, s->bvh, TracerBackend::kPacket);
  PathSettings settings;
  settings.integrator = integrator;
  settings.spp = 1;
  settings.time_phases = phases;
  const double pixels = double(s->parsed.scene.width) * s->parsed.scene.height;
  double samples = 0, rays = 0;
  PathStats all;
  for (auto _ : state) {
    PathStats stats;
    render_path(tracer, settings, &stats);
    ++settings.seed;
    samples += pixels;
    rays += double(stats.rays());
    all.phases.add(stats.phases);
    all.bounce_rays += stats.bounce_rays, all.shadow_rays += stats.shadow_rays;
    all.camera_rays += stats.camera_rays, all.steps += stats.steps;
  }
  state.counters["samples/s"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
  state.counters["rays/s"] = benchmark::Counter(rays, benchmark::Counter::kIsRate);
  if (phases && all.phases.trace_rest > 0) {
    // Per thread-second of tracing, as --stats reports it.
    state.counters["traced Mrays/s"] =
        double(all.bounce_rays + all.shadow_rays) / all.phases.trace_rest * 1e-6;
    state.counters["shade/trace"] =
        (all.phases.shade + all.phases.lights) / (all.phases.trace_rest + all.phases.trace_camera);
    // How full the wavefronts ran (src/render/wavefront/render_loop.h).
    state.counters["rays/step"] = double(all.rays()) / double(std::max<uint64_t>(all.steps, 1));
  }
}

void register_all() {
  const int all = omp_get_num_procs();
  auto add = [](const std::string& scene, Integrator integrator, int threads, bool phases) {
    std::string name = "render/" + scene + "/" + std::string(integrator_name(integrator)) +
                       (phases ? "/phases" : "") + "/threads:" + std::to_string(threads);
    benchmark::RegisterBenchmark(name.c_str(), render_passes, scene, integrator, threads, phases)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  };
  // The bunny's mesh is made by a tool, not by the build: without it its rows are left out
  // (said once), not failed, so a fresh build's benchmarks still run through.
  const bool bunny =
      std::filesystem::is_regular_file(std::string(RAYLANE_BENCH_DATA) + "/bunny-scan.ply");
  if (!bunny)
    std::fprintf(stderr,
                 "bench_render: testscene-bunny left out; run tools/make_bunny --scan-units "
                 "build/bench-data/bunny-scan.ply first\n");
  for (const char* scene :
       {"testscene", "testscene-glass", "testscene-mirror", "testscene-bunny", "icosphere", "csg",
        "testscene-textured", "testscene-sky", "testscene-boxlight", "testscene-bulb"}) {
    if (std::string_view(scene) == "testscene-bunny" && !bunny) continue;
    for (Integrator integrator : {Integrator::kMis, Integrator::kNee, Integrator::kBrdf})
      for (int threads : {1, all}) {
        add(scene, integrator, threads, false);
        if (all == 1) break;
      }
    add(scene, Integrator::kMis, 1, true);
  }
}

}  // namespace
}  // namespace raylane::bench

int main(int argc, char** argv) {
  raylane::bench::register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
