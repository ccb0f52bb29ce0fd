// `raylane trace MESH RAYS`: traces an external ray set (docs/ray-sets.md) with the packet
// tracer (or a reference backend, --tracer), prints the median speed of several runs and writes
// the answers as a .hits file, so raylane and any other tracer can be compared on identical
// rays; --stats-json adds what the traversal did (nodes, primitives and lanes per ray).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "args.h"
#include "commands.h"
#include "file_roles.h"
#include "json_text.h"
#include "raylane/bvh/bvh.h"
#include "raylane/core/atomic_file.h"
#include "raylane/core/parallel.h"
#include "raylane/core/strings.h"
#include "raylane/image/write_image.h"
#include "raylane/scene/mesh_import.h"
#include "raylane/trace/ray_set_io.h"
#include "raylane/trace/simd_tracer.h"
#include "raylane/trace/tracer.h"

namespace raylane::cli {

namespace {

struct TraceRequest {
  std::string mesh, rays, output;
  std::optional<std::string> stats_json;
  TracerBackend tracer = TracerBackend::kPacket;
  Isa isa = best_isa();
  int threads = 0, repeat = 5;
  bool quiet = false;
};

const std::vector<OptionSpec> kTraceOptions = {
    {"output", 'o', "FILE", false, "the answers, as .hits",
     "the ray set's name with .hits, in the working directory"},
    {"repeat", 0, "N", false, "runs to take the median of", "5"},
    {"tracer", 0, "T", false,
     cat(kTracerBackendNames.list(),
         ": SIMD packets through the BVH; single rays\n"
         "through the BVH with the double kernels; brute force with the double kernels"),
     "packet"},
    {"isa", 0, "I", false, cat(kIsaNames.list(), ", auto: the packet tracer's instruction set"),
     "auto, the widest this CPU has"},
    {"stats-json", 0, "FILE", false,
     "write the summary (rays, Mrays/s of each run, tracer, ISA, threads, BVH) and, for\n"
     "the packet tracer, nodes, leaves and primitives tested per ray and the lanes used,\n"
     "as one JSON object (docs/ray-sets.md, \"raylane trace\")",
     "none"},
    {"threads", 0, "N", false, "worker threads, 0 = all cores", "0"},
    {"quiet", 'q', "", false, "print only errors and the written file's path", ""},
};

const CommandHelp kTraceHelp{
    "raylane trace MESH RAYS [options]",
    "Traces an external ray set (.rays) against a mesh (a .tris soup, or any mesh file Assimp\n"
    "reads) with the packet tracer, prints the median Mrays/s and writes the answers (.hits), so\n"
    "raylane and any other tracer can be compared on identical rays. Closest hit or occlusion,\n"
    "as the ray set says. The file formats: docs/ray-sets.md.",
    &kTraceOptions, ""};

Result<TraceRequest> read_request(const std::vector<std::string>& args) {
  auto parsed = parse_args(args, kTraceOptions);
  if (!parsed) return Error{parsed.error()};
  if (parsed->positional.size() != 2)
    return Error{cat("trace takes a mesh (.tris, or any mesh file) and a ray set (.rays), found ",
                     parsed->positional.size(), " arguments")};
  TraceRequest r;
  r.mesh = parsed->positional[0];
  r.rays = parsed->positional[1];
  r.output = parsed->last("output").value_or(
      std::filesystem::path(r.rays).replace_extension(".hits").filename().string());
  if (auto t = parsed->last("tracer")) {
    auto kind = tracer_backend_from_name(*t);
    if (!kind)
      return Error{cat("unknown --tracer ", in_quotes(*t), " (", kTracerBackendNames.list(), ")")};
    r.tracer = *kind;
  }
  r.stats_json = parsed->last("stats-json");
  if (auto i = parsed->last("isa")) {
    auto isa = parse_isa_option(*i);
    if (!isa) return Error{isa.error()};
    r.isa = *isa;
  }
  if (auto t = parsed->last("threads"))
    if (Status s = read_int_option("threads", *t, 0, 4096, r.threads); !s) return Error{s.error()};
  if (auto n = parsed->last("repeat"))
    if (Status s = read_int_option("repeat", *n, 1, 1000, r.repeat); !s) return Error{s.error()};
  r.quiet = parsed->has("quiet");
  return r;
}

// The mesh as a scene of triangles, in the file's order; `files` receives what was read.
Result<Scene> load_mesh(const std::string& path, std::vector<std::string>& files) {
  Scene s;
  s.materials.push_back(Material::default_grey());
  TriangleTable& t = s.table<Triangle>();
  if (std::filesystem::path(path).extension() == ".tris") {
    auto n = read_triangle_soup(path, 0, t);
    if (!n) return Error{n.error()};
    files.push_back(path);
  } else {
    auto n = import_mesh_file(path, MeshPlacement{}, 0, t);
    if (!n) return Error{n.error()};
    files = n->files;
  }
  return s;
}

// The answers in the file's terms: triangle indices of the input, not of the BVH's order.
std::vector<HitRecord> to_records(const HitStream& hits, const Bvh& bvh, bool occlusion) {
  const auto& source = bvh.source_rows[uint32_t(tag_of<Triangle>)];
  std::vector<HitRecord> out(hits.t.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    bool hit = hits.prim[i] != PrimRef::kInvalidBits;
    if (occlusion) {
      out[i] = {0.0f, hit ? 0u : kNoHit};
    } else {
      out[i] = {hits.t[i], hit ? source[PrimRef::from_bits(hits.prim[i]).row()] : kNoHit};
    }
  }
  return out;
}

// One run over the whole set, split over the threads in chunks of whole packets (as one pass
// would make them). The reference backends (--tracer bvh, scalar) trace each chunk as a stream
// of its own, with their double kernels, and their answers are written back in float.
void trace_all(const Scene& scene, const Bvh& bvh, const RayStream& rays, bool occlusion,
               const TraceRequest& r, const SimdTracer& simd, HitStream& hits) {
  if (r.tracer == TracerBackend::kPacket) {
    parallel_chunks(rays.size(), kTraceChunk, [&](std::size_t begin, std::size_t end) {
      simd.trace_range(scene, bvh, rays, begin, end, hits, occlusion);
    });
    return;
  }
  const Tracer reference(scene, bvh, r.tracer, r.isa);
  parallel_chunks(rays.size(), kTraceChunk, [&](std::size_t begin, std::size_t end) {
    TraceScratch scratch;
    RayStream chunk;
    chunk.resize(end - begin);
    for (std::size_t i = begin; i < end; ++i)
      chunk.set(i - begin, rays.get(i));
    if (occlusion) {
      std::vector<uint8_t> blocked;
      reference.occluded(chunk, blocked, scratch);
      for (std::size_t i = begin; i < end; ++i)
        hits.prim[i] = blocked[i - begin] ? 0u : PrimRef::kInvalidBits;
      return;
    }
    std::vector<Hit> answers;
    reference.closest(chunk, answers, 0, scratch);
    for (std::size_t i = begin; i < end; ++i) {
      hits.t[i] = float(answers[i - begin].t);
      hits.prim[i] = answers[i - begin].prim.bits();
    }
  });
}

// What `trace` measured, for the summary line and --stats-json.
struct TraceSummary {
  std::vector<double> seconds;                // each run's wall time, sorted
  std::optional<TraversalCounters> counters;  // the packet tracer's, with --stats-json
  double median() const { return seconds[seconds.size() / 2]; }
};

// {"mesh": ..., "ray_set": ..., "rays": N, ..., "traversal": {...} or null, "outputs": [...]}
// (the keys: docs/ray-sets.md, "raylane trace").
std::string trace_json(const TraceRequest& r, const Scene& scene, const Bvh& bvh,
                       const RaySetFile& set, const TraceSummary& m) {
  const double n = double(set.rays.size());
  JsonObject o;
  o.string("mesh", r.mesh).string("ray_set", r.rays).count("rays", set.rays.size());
  o.string("query", set.occlusion() ? "occlusion" : "closest");
  o.count("triangles", scene.table<Triangle>().size()).count("runs", m.seconds.size());
  o.number("seconds", m.median());
  o.number("mrays_per_second", n / m.median() * 1e-6);
  o.number("mrays_per_second_slowest", n / m.seconds.back() * 1e-6);
  o.number("mrays_per_second_fastest", n / m.seconds.front() * 1e-6);
  o.string("tracer", tracer_backend_name(r.tracer)).string("isa", isa_name(r.isa));
  o.count("threads", uint64_t(omp_get_max_threads()));
  if (const auto& c = m.counters)
    o.raw("traversal", JsonObject()
                           .count("lanes", uint64_t(c->width))
                           .number("nodes_per_ray", c->per_ray(c->node_tests))
                           .number("leaves_per_ray", c->per_ray(c->leaf_visits))
                           .number("prims_per_ray", c->per_ray(c->prim_tests))
                           .number("lanes_used", c->lane_utilisation())
                           .number("single_rays_per_ray", c->per_ray(c->single_rays))
                           .str());
  else
    o.raw("traversal", "null");
  o.raw("bvh", JsonObject()
                   .count("nodes", bvh.nodes.size())
                   .count("wide_nodes", bvh.wide.nodes.size())
                   .number("build_seconds", bvh.stats.build_seconds)
                   .str());
  o.raw("outputs", json_string_array({r.output}));
  return o.str() + "\n";
}

// The request's inputs and outputs checked before anything is traced: no output is an input
// (the ray set, a mesh file) or another output, and each can be written.
Status outputs_apart(const TraceRequest& r, const std::vector<std::string>& mesh_files) {
  std::vector<FileRole> inputs = {{r.rays, "the ray set"}}, outputs = {{r.output, "the output"}};
  for (const std::string& f : mesh_files)
    inputs.push_back({f, "a mesh file"});
  if (r.stats_json) outputs.push_back({*r.stats_json, "the --stats-json file"});
  return check_outputs_apart(inputs, outputs);
}

bool outputs_writable(const TraceRequest& r) {
  std::vector<std::string> all = {r.output};
  if (r.stats_json) all.push_back(*r.stats_json);
  for (const std::string& out : all)
    if (Status s = check_writable(out); !s) {
      std::fprintf(stderr, "raylane: cannot write %s: %s\n", out.c_str(), s.error().c_str());
      return false;
    }
  return true;
}

void print_summary(const TraceRequest& r, const Scene& scene, const Bvh& bvh, const RaySetFile& set,
                   const TraceSummary& m) {
  const double n = double(set.rays.size());
  std::fprintf(stderr,
               "traced %s (%s) against %s: median %.2f Mrays/s over %s "
               "(%.2f … %.2f); %s, %s; BVH built in %.3f s\n",
               counted(set.rays.size(), "ray").c_str(),
               set.occlusion() ? "occlusion" : "closest hit",
               counted(scene.table<Triangle>().size(), "triangle").c_str(), n / m.median() * 1e-6,
               counted(int(m.seconds.size()), "run").c_str(), n / m.seconds.back() * 1e-6,
               n / m.seconds.front() * 1e-6,
               r.tracer == TracerBackend::kPacket
                   ? cat(isa_name(r.isa), " packets").c_str()
                   : cat("the ", tracer_backend_name(r.tracer), " reference").c_str(),
               counted(omp_get_max_threads(), "thread").c_str(), bvh.stats.build_seconds);
}

}  // namespace

int trace_command(const std::vector<std::string>& args) {
  if (asks_for_help(args, kTraceOptions)) return print_help(kTraceHelp);
  auto request = read_request(args);
  if (!request) return usage_error("trace", request.error());
  const TraceRequest& r = *request;
  // Outputs never eat inputs: checked before the mesh is read, then with every file it named.
  if (Status s = outputs_apart(r, {}); !s) return usage_error("trace", s.error());
  std::vector<std::string> mesh_files;
  auto scene = load_mesh(r.mesh, mesh_files);
  if (!scene) {
    std::fprintf(stderr, "raylane: %s\n", scene.error().c_str());
    return kExitUsage;
  }
  if (Status s = outputs_apart(r, mesh_files); !s) return usage_error("trace", s.error());
  auto set = read_ray_set(r.rays);
  if (!set) {
    std::fprintf(stderr, "raylane: %s\n", set.error().c_str());
    return kExitUsage;
  }
  if (!outputs_writable(r)) return kExitUsage;
  if (r.threads > 0) omp_set_num_threads(r.threads);

  Bvh bvh = build_bvh_and_reorder(*scene, render_bvh_config(*scene));
  SimdTracer tracer(r.isa);
  HitStream hits;
  hits.resize(set->rays.size());
  TraceSummary m;
  for (int i = 0; i < r.repeat; ++i) {
    auto start = std::chrono::steady_clock::now();
    trace_all(*scene, bvh, set->rays, set->occlusion(), r, tracer, hits);
    m.seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(m.seconds.begin(), m.seconds.end());
  // The counters come from one more, instrumented run (the timed runs carry none); its
  // answers are the same, and the ones written are the last timed run's.
  if (r.stats_json && r.tracer == TracerBackend::kPacket) {
    HitStream counted_hits;
    m.counters = tracer.trace_counted(*scene, bvh, set->rays, counted_hits, set->occlusion());
  }
  if (Status s = write_hits(r.output, to_records(hits, bvh, set->occlusion()), set->flags); !s) {
    std::fprintf(stderr, "raylane: %s\n", s.error().c_str());
    return kExitFailure;
  }
  if (r.stats_json) {
    Status s = write_file_atomically(*r.stats_json, trace_json(r, *scene, bvh, *set, m));
    if (!s) {
      std::fprintf(stderr, "raylane: cannot write %s: %s\n", r.stats_json->c_str(),
                   s.error().c_str());
      return kExitFailure;
    }
  }
  std::printf("%s\n", r.output.c_str());
  if (!r.quiet) print_summary(r, *scene, bvh, *set, m);
  return kExitOk;
}

}  // namespace raylane::cli
