// Whole path-traced renders, timed (issue 14's yardstick): samples per second — pixels ×
// passes over wall time — of the course scene, its glass and mirror variants and a large mesh
// (the benchmark's 1.31M-triangle displaced icosphere, glossy, under a sphere light), per
// integrator, on 1 and all threads. One pass at the scene's own resolution per iteration,
// each with its own seed, so every iteration does the same kind of work.
//
//   build/bench/bench_render [--benchmark_filter=...] [--benchmark_repetitions=5 ...]
#include <benchmark/benchmark.h>
#include <omp.h>

#include <map>
#include <memory>
#include <mutex>
#include <string>

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
    else
      s->parsed = load_scene_file(std::string(RAYLANE_SOURCE_DIR) + "/scenes/" + name + ".scn");
    if (!s->parsed.ok()) return nullptr;
    s->bvh = build_bvh(s->parsed.scene);
    slot = std::move(s);
  }
  return slot.get();
}

void render_passes(benchmark::State& state, const std::string& name, Integrator integrator,
                   int threads) {
  const RenderScene* s = render_scene(name);
  if (!s) return state.SkipWithError(("cannot load scene " + name).c_str());
  omp_set_num_threads(threads);
  Tracer tracer(s->parsed.scene, s->bvh, TracerKind::kPacket);
  PathSettings settings;
  settings.integrator = integrator;
  settings.spp = 1;
  const double pixels = double(s->parsed.scene.width) * s->parsed.scene.height;
  double samples = 0, rays = 0;
  for (auto _ : state) {
    PathStats stats;
    render_path(tracer, settings, &stats);
    ++settings.seed;
    samples += pixels;
    rays += double(stats.rays());
  }
  state.counters["samples/s"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
  state.counters["rays/s"] = benchmark::Counter(rays, benchmark::Counter::kIsRate);
}

void register_all() {
  const int all = omp_get_num_procs();
  for (const char* scene : {"testscene", "testscene-glass", "testscene-mirror", "icosphere"})
    for (Integrator integrator : {Integrator::kMis, Integrator::kNee, Integrator::kBrdf})
      for (int threads : {1, all}) {
        std::string name = std::string("render/") + scene + "/" +
                           std::string(integrator_name(integrator)) +
                           "/threads:" + std::to_string(threads);
        benchmark::RegisterBenchmark(name.c_str(), render_passes, scene, integrator, threads)
            ->UseRealTime()
            ->Unit(benchmark::kMillisecond);
        if (all == 1) break;
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
