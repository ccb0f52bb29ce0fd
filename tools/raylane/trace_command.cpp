// `raylane trace MESH RAYS`: traces an external ray set (docs/ray-sets.md) with the packet
// tracer, prints the median speed of several runs and writes the answers as a .hits file, so
// raylane and any other tracer can be compared on identical rays.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "args.h"
#include "commands.h"
#include "file_roles.h"
#include "raylane/bvh/bvh.h"
#include "raylane/core/parallel.h"
#include "raylane/core/strings.h"
#include "raylane/image/write_image.h"
#include "raylane/scene/mesh_import.h"
#include "raylane/trace/ray_set_io.h"
#include "raylane/trace/simd_tracer.h"

namespace raylane::cli {

namespace {

struct TraceRequest {
  std::string mesh, rays, output;
  Isa isa = best_isa();
  int threads = 0, repeat = 5;
  bool quiet = false;
};

const std::vector<OptionSpec> kTraceOptions = {
    {"output", 'o', "FILE", false, "the answers, as .hits",
     "the ray set's name with .hits, in the working directory"},
    {"repeat", 0, "N", false, "runs to take the median of", "5"},
    {"isa", 0, "I", false, cat(kIsaNames.list(), ", auto: the packet tracer's instruction set"),
     "auto, the widest this CPU has"},
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

}  // namespace

int trace_command(const std::vector<std::string>& args) {
  if (asks_for_help(args, kTraceOptions)) return print_help(kTraceHelp);
  auto request = read_request(args);
  if (!request) return usage_error("trace", request.error());
  const TraceRequest& r = *request;
  // Outputs never eat inputs: the answers may not overwrite the ray set or the mesh.
  std::vector<FileRole> inputs = {{r.rays, "the ray set"}};
  if (Status s = check_outputs_apart(inputs, {{r.output, "the output"}}); !s)
    return usage_error("trace", s.error());
  std::vector<std::string> mesh_files;
  auto scene = load_mesh(r.mesh, mesh_files);
  if (!scene) {
    std::fprintf(stderr, "raylane: %s\n", scene.error().c_str());
    return kExitUsage;
  }
  for (const std::string& f : mesh_files)
    inputs.push_back({f, "a mesh file"});
  if (Status s = check_outputs_apart(inputs, {{r.output, "the output"}}); !s)
    return usage_error("trace", s.error());
  auto set = read_ray_set(r.rays);
  if (!set) {
    std::fprintf(stderr, "raylane: %s\n", set.error().c_str());
    return kExitUsage;
  }
  if (Status s = check_writable(r.output); !s) {
    std::fprintf(stderr, "raylane: cannot write %s: %s\n", r.output.c_str(), s.error().c_str());
    return kExitUsage;
  }
  if (r.threads > 0) omp_set_num_threads(r.threads);

  Bvh bvh = build_bvh_and_reorder(*scene, render_bvh_config(*scene));
  SimdTracer tracer(r.isa);
  HitStream hits;
  hits.resize(set->rays.size());
  std::vector<double> seconds;
  for (int i = 0; i < r.repeat; ++i) {
    auto start = std::chrono::steady_clock::now();
    // This command owns the threads: chunks of whole packets, as one pass would make them.
    parallel_chunks(set->rays.size(), kTraceChunk, [&](std::size_t begin, std::size_t end) {
      tracer.trace_range(*scene, bvh, set->rays, begin, end, hits, set->occlusion());
    });
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  double median = seconds[seconds.size() / 2];
  if (Status s = write_hits(r.output, to_records(hits, bvh, set->occlusion()), set->flags); !s) {
    std::fprintf(stderr, "raylane: %s\n", s.error().c_str());
    return kExitFailure;
  }
  std::printf("%s\n", r.output.c_str());
  if (!r.quiet)
    std::fprintf(stderr,
                 "traced %s (%s) against %s: median %.2f Mrays/s over %s "
                 "(%.2f … %.2f); %s packets, %s; BVH built in %.3f s\n",
                 counted(set->rays.size(), "ray").c_str(),
                 set->occlusion() ? "occlusion" : "closest hit",
                 counted(scene->table<Triangle>().size(), "triangle").c_str(),
                 set->rays.size() / median * 1e-6, counted(r.repeat, "run").c_str(),
                 set->rays.size() / seconds.back() * 1e-6, set->rays.size() / seconds[0] * 1e-6,
                 std::string(isa_name(r.isa)).c_str(),
                 counted(omp_get_max_threads(), "thread").c_str(), bvh.stats.build_seconds);
  return kExitOk;
}

}  // namespace raylane::cli
