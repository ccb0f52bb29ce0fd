// raylane's benchmark suite (docs/benchmarks.md, "Programs"): rays per second of every tracer on
// identical ray sets of every benchmark scene, at 1 thread and at all threads, after checking each
// tracer's answers against the double-precision reference; and BVH build time and memory next to
// Embree's. `tools/bench_table` runs it with repetitions and prints the median table;
// `bench_trace --export=DIR` writes the triangle scenes and their ray sets as files.
#include <benchmark/benchmark.h>
#include <omp.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "bench_scenes.h"
#include "embree_tracer.h"
#include "ply_export.h"
#include "ray_sets.h"
#include "raylane/prims/table_util.h"
#include "raylane/trace/ray_set_io.h"
#include "tracers.h"

namespace raylane::bench {
namespace {

// Agreement is checked on at most this many rays per set (every k-th ray).
constexpr std::size_t kCheckedRays = 1 << 15;
// A tracer whose answers differ from the reference on more rays than this fails: rays in
// the ambiguous band (silhouettes, shared edges at float precision) are a few in 10^5.
constexpr double kMaxDisagreement = 1e-3;

// Flush denormals to zero on every worker thread, for every tracer alike (Embree's API
// documentation recommends it; docs/benchmarks.md, "Denormals").
void use_threads(int threads) {
  omp_set_num_threads(threads);
#pragma omp parallel
  {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  }
}

// One tracer on one ray set of one scene: checked against the reference, counted, timed.
void trace_set(benchmark::State& state, const BenchScene* b, const RaySet& set,
               const std::string& tracer, int threads) {
  BenchTracer t = bench_tracer(*b, tracer);
  use_threads(threads);
  HitStream hits;
  t.trace(set.rays, set.occlusion, hits);
  std::size_t stride = std::max<std::size_t>(1, set.rays.size() / kCheckedRays);
  Agreement a = check_against_reference(*b, set.rays, set.occlusion, hits, stride);
  state.counters["disagree"] = a.rate();
  if (a.rate() > kMaxDisagreement)
    return state.SkipWithError(("answers disagree with the reference on " +
                                std::to_string(a.disagree) + " of " + std::to_string(a.checked) +
                                " rays")
                                   .c_str());
  if (t.count) {
    TraversalCounters c = t.count(set.rays, set.occlusion, hits);
    state.counters["nodes/ray"] = c.per_ray(c.node_tests);
    state.counters["prims/ray"] = c.per_ray(c.prim_tests);
    state.counters["lanes_used"] = c.lane_utilisation();
    state.counters["leaves/ray"] = c.per_ray(c.leaf_visits);
  }
  for (auto _ : state) {
    t.trace(set.rays, set.occlusion, hits);
    benchmark::DoNotOptimize(hits.t.data());
  }
  state.counters["rays"] = double(set.rays.size());
  state.counters["rays/s"] = benchmark::Counter(
      double(set.rays.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
}

void trace_rays(benchmark::State& state, const std::string& scene, RayKind kind,
                const std::string& tracer, int threads) {
  std::string why;
  const BenchScene* b = bench_scene(scene, &why);
  if (!b) return state.SkipWithError(why.c_str());
  trace_set(state, b, bench_rays(*b, kind), tracer, threads);
}

// A user's own ray set against a user's mesh (--rays and --mesh, or RAYLANE_BENCH_RAYS and
// RAYLANE_BENCH_MESH): every tracer, Embree's included, on the user's rays, in the same table.
struct UserSet {
  std::string mesh, rays;
};

UserSet& user_set() {
  static UserSet u;
  return u;
}

// The user's rays, read once (the file's checks: docs/ray-sets.md); null with the reason.
const RaySet* user_rays(std::string* why) {
  static std::optional<RaySet> set;
  static std::string error;
  if (!set && error.empty()) {
    auto file = read_ray_set(user_set().rays);
    if (file)
      set = RaySet{std::move(file->rays), file->occlusion()};
    else
      error = file.error();
  }
  *why = error;
  return set ? &*set : nullptr;
}

void trace_user_rays(benchmark::State& state, const std::string& tracer, int threads) {
  std::string why;
  const BenchScene* b = bench_scene(std::string(kUserMeshPrefix) + user_set().mesh, &why);
  if (!b) return state.SkipWithError(why.c_str());
  const RaySet* set = user_rays(&why);
  if (!set) return state.SkipWithError(why.c_str());
  trace_set(state, b, *set, tracer, threads);
}

// trace/<mesh>/<rays>/<tracer>/threads:N, the file stems in the scene's and the kind's places
// (tools/bench_table reads them as such).
void register_user_set() {
  const UserSet& u = user_set();
  const std::string stem = std::filesystem::path(u.mesh).stem().string() + "/" +
                           std::filesystem::path(u.rays).stem().string();
  const int all = omp_get_num_procs();
  for (const std::string& tracer : bench_tracer_names())
    for (int threads : {1, all}) {
      std::string name = "trace/" + stem + "/" + tracer + "/threads:" + std::to_string(threads);
      benchmark::RegisterBenchmark(name.c_str(), trace_user_rays, tracer, threads)
          ->UseRealTime()
          ->Unit(benchmark::kMillisecond);
      if (all == 1) break;
    }
}

std::size_t table_bytes_of(Scene& s) {
  std::size_t bytes = 0;
  PrimKinds::for_each([&](auto kind) { bytes += table_bytes(s.table<decltype(kind)>()); });
  return bytes;
}

void build_raylane(benchmark::State& state, const std::string& scene, int threads) {
  std::string why;
  const BenchScene* b = bench_scene(scene, &why);
  if (!b) return state.SkipWithError(why.c_str());
  use_threads(threads);
  std::size_t bytes = 0, wide_bytes = 0;
  double sah = 0;
  // Timed like Embree's build (build_embree): the call that builds, from the scene's tables to
  // the finished tree and permuted tables, by the wall clock; not the copy of the scene it
  // permutes, nor freeing the tree and the copy (Embree's rtcReleaseScene is not timed either),
  // nor Pause/ResumeTiming, whose CPU clock reads are system calls (1.5 µs of the course
  // scene's 15 in the same binary, 5 interleaved rounds).
  for (auto _ : state) {
    Scene copy = b->scene;
    auto start = std::chrono::steady_clock::now();
    Bvh bvh = build_bvh_and_reorder(copy);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    bytes = bvh.bytes() + table_bytes_of(copy);
    sah = bvh.stats.sah_cost;
    wide_bytes = collapse_to_wide(bvh).bytes();  // what single rays over the 8-wide tree add
  }
  state.counters["sah_cost"] = sah;
  double prims = double(b->scene.primitive_count());
  state.counters["prims"] = prims;
  state.counters["bytes/prim"] = double(bytes) / prims;
  state.counters["wide_bytes/prim"] = double(wide_bytes) / prims;
}

void build_embree(benchmark::State& state, const std::string& scene) {
  std::string why;
  const BenchScene* b = bench_scene(scene, &why);
  if (!b) return state.SkipWithError(why.c_str());
  EmbreeBuild last;
  for (auto _ : state) {
    last = embree_build_once(*b);
    state.SetIterationTime(last.seconds);
  }
  double prims = double(b->scene.primitive_count());
  state.counters["prims"] = prims;
  state.counters["bytes/prim"] = double(last.bytes) / prims;
}

void register_all() {
  if (!user_set().rays.empty()) register_user_set();
  const int all = omp_get_num_procs();
  for (const std::string& scene : bench_scene_names()) {
    for (RayKind kind : {RayKind::kPrimary, RayKind::kShadow, RayKind::kDiffuse})
      for (const std::string& tracer : bench_tracer_names())
        for (int threads : {1, all}) {
          std::string name = "trace/" + scene + "/" + ray_kind_name(kind) + "/" + tracer +
                             "/threads:" + std::to_string(threads);
          benchmark::RegisterBenchmark(name.c_str(), trace_rays, scene, kind, tracer, threads)
              ->UseRealTime()
              ->Unit(benchmark::kMillisecond);
          if (all == 1) break;
        }
    for (int threads : {1, all}) {
      std::string name = "build/" + scene + "/raylane/threads:" + std::to_string(threads);
      benchmark::RegisterBenchmark(name.c_str(), build_raylane, scene, threads)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
      if (all == 1) break;
    }
    if (embree_available())
      benchmark::RegisterBenchmark(("build/" + scene + "/embree/threads:all").c_str(), build_embree,
                                   scene)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
  }
}

// --export DIR: writes every triangle scene as DIR/<scene>.tris and its ray sets as
// DIR/<scene>-<rays>.rays (docs/ray-sets.md), for other tracers to run the identical rays,
// and as DIR/<scene>.ply, for scene files to render (bench/scenes/).
int export_sets(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return std::fprintf(stderr, "cannot make %s: %s\n", dir.c_str(), ec.message().c_str()), 1;
  for (const std::string& name : bench_scene_names()) {
    std::string why;
    const BenchScene* b = bench_scene(name, &why);
    if (!b) {
      std::fprintf(stderr, "skipping %s: %s\n", name.c_str(), why.c_str());
      continue;
    }
    if (b->scene.primitive_count() != b->scene.table<Triangle>().size()) continue;
    std::vector<Status> done = {
        write_triangle_soup(dir + "/" + name + ".tris", b->scene.table<Triangle>()),
        write_ply_soup(dir + "/" + name + ".ply", b->scene.table<Triangle>())};
    for (RayKind kind : {RayKind::kPrimary, RayKind::kShadow, RayKind::kDiffuse}) {
      const RaySet& set = bench_rays(*b, kind);
      RaySetFile file{set.rays, set.occlusion ? kRaySetOcclusionFlag : 0, 0, 0};
      if (kind == RayKind::kPrimary) file.width = b->scene.width, file.height = b->scene.height;
      done.push_back(write_ray_set(dir + "/" + name + "-" + ray_kind_name(kind) + ".rays", file));
    }
    for (const Status& st : done)
      if (!st) return std::fprintf(stderr, "%s\n", st.error().c_str()), 1;
    std::printf("wrote %s/%s.tris, .ply and its ray sets\n", dir.c_str(), name.c_str());
  }
  return 0;
}

}  // namespace
}  // namespace raylane::bench

constexpr const char* kUsage =
    R"(usage: bench_trace [--bunny=FILE] [--export=DIR | Google Benchmark flags]

Rays per second of every tracer on identical ray sets of every benchmark scene (testscene,
bunny, engine, icosphere, sphereflake, lattice), at 1 thread and at all threads, after checking
each tracer's answers against the double-precision reference; BVH builds next to Embree's.
tools/bench_table runs it with repetitions and prints the median table (bench/README.md).

  --export=DIR   write every triangle scene as DIR/<scene>.tris and DIR/<scene>.ply and its
                 ray sets as DIR/<scene>-<primary|shadow|diffuse>.rays (docs/ray-sets.md), then
                 exit; DIR is made if missing
  --bunny=FILE   the bunny's PLY (default: bench-data/bunny.ply of the build tree this program
                 is in, where tools/make_bunny writes it; without it the bunny is skipped)
  --rays=FILE    also trace a user's ray set (.rays, docs/ray-sets.md) with every tracer,
                 Embree's included, against --mesh, as trace/<mesh>/<rays>/<tracer>/threads:N
                 (default: none; environment: RAYLANE_BENCH_RAYS, so tools/bench_table runs it)
  --mesh=FILE    the triangles of --rays: a .tris soup or any mesh file Assimp reads, as
                 `raylane trace` reads them (default: none; environment: RAYLANE_BENCH_MESH)

Google Benchmark's own flags follow, e.g. --benchmark_filter=REGEX:
)";

// --rays and --mesh, or their environment variables; false (with a message) when only one of
// the two is given.
bool read_user_set(int argc, char** argv) {
  auto& u = raylane::bench::user_set();
  if (const char* r = std::getenv("RAYLANE_BENCH_RAYS")) u.rays = r;
  if (const char* m = std::getenv("RAYLANE_BENCH_MESH")) u.mesh = m;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--rays=", 0) == 0) u.rays = a.substr(7);
    if (a.rfind("--mesh=", 0) == 0) u.mesh = a.substr(7);
  }
  if (u.rays.empty() == u.mesh.empty()) return true;
  std::fprintf(stderr,
               "bench_trace: expected --rays=FILE and --mesh=FILE together, found only %s\n",
               u.rays.empty() ? "--mesh" : "--rays");
  return false;
}

bool ours(const std::string& a) {
  return a.rfind("--bunny=", 0) == 0 || a.rfind("--rays=", 0) == 0 || a.rfind("--mesh=", 0) == 0;
}

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--help" || a == "-h") std::fputs(kUsage, stdout);
    if (a.rfind("--bunny=", 0) == 0) raylane::bench::set_bunny_path(a.substr(8));
  }
  if (!read_user_set(argc, argv)) return 2;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--export=", 0) == 0) return raylane::bench::export_sets(a.substr(9));
  }
  // --bunny, --rays and --mesh are ours: Google Benchmark would reject them as unrecognised.
  int kept = 1;
  for (int i = 1; i < argc; ++i)
    if (!ours(argv[i])) argv[kept++] = argv[i];
  argc = kept;
  raylane::bench::register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
