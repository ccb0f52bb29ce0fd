// `raylane info`: what was modelled — rows and bytes per table, materials, lights, camera.
#include <cstdio>
#include <string>

#include "args.h"
#include "commands.h"
#include "film_info.h"
#include "raylane/bvh/bvh.h"
#include "raylane/core/memory.h"
#include "raylane/core/strings.h"
#include "raylane/image/input_image.h"
#include "raylane/prims/table_util.h"
#include "raylane/scene/mesh_import.h"
#include "raylane/simd/isa.h"

namespace raylane::cli {

namespace {

void print_tables(Scene& s) {
  std::printf("tables (rows, bytes):\n");
  std::size_t total = 0;
  PrimKinds::for_each([&](auto kind) {
    using Kind = decltype(kind);
    auto& t = s.table<Kind>();
    std::size_t bytes = table_bytes(t);
    total += bytes;
    if (t.size() > 0)
      std::printf("  %-10s %10zu rows %12zu bytes\n", std::string(Kind::plural).c_str(), t.size(),
                  bytes);
  });
  std::printf("  %-10s %10zu rows %12zu bytes\n", "total", s.primitive_count(), total);
  if (s.table<Triangle>().has_uv())
    std::printf("  (triangles include %zu bytes of texture coordinates)\n",
                s.table<Triangle>().t0u.size() * 6 * sizeof(float));
}

// Each csg block in the order written: its leaves, its postfix program, its bounds.
void print_csg_blocks(const Scene& s) {
  const CsgTable& c = s.table<Csg>();
  static constexpr const char* kLeafNames[] = {"sphere", "box", "cylinder"};
  for (uint32_t b = 0; b < c.size(); ++b) {
    std::printf("csg block %u: %u leaves (", b, c.leaf_count[b]);
    for (uint32_t i = 0; i < c.leaf_count[b]; ++i)
      std::printf("%s%s", i ? " " : "", kLeafNames[c.leaf_kind[c.leaf_begin[b] + i]]);
    std::printf("), program");
    for (uint32_t code : c.program_of(b)) {
      if (code < kCsgMaxLeaves)
        std::printf(" %u", code);
      else
        std::printf(" %s", std::string(csg_code_name(code)).c_str());
    }
    Bounds3f bb = c.bounds(b);
    std::printf(", bounds (%g %g %g) to (%g %g %g)\n", bb.lo.x, bb.lo.y, bb.lo.z, bb.hi.x, bb.hi.y,
                bb.hi.z);
  }
}

// Each sdf block in the order written: its leaves, its postfix program (a smooth operator with
// its k), its bounds (widened by k).
void print_sdf_blocks(const Scene& s) {
  const SdfTable& t = s.table<Sdf>();
  static constexpr const char* kLeafNames[] = {"sphere", "box", "cylinder", "torus"};
  for (uint32_t row = 0; row < t.size(); ++row) {
    const uint32_t b = t.block[row];
    std::printf("sdf block %u: %u leaves (", b, t.leaf_count[b]);
    for (uint32_t i = 0; i < t.leaf_count[b]; ++i)
      std::printf("%s%s", i ? " " : "", kLeafNames[t.leaf_kind[t.leaf_begin[b] + i]]);
    std::printf("), program");
    for (uint32_t j = t.program_begin[b]; j < t.program_begin[b] + t.program_count[b]; ++j) {
      const uint32_t code = t.program[j];
      if (code < kSdfMaxLeaves)
        std::printf(" %u", code);
      else if (sdf_is_smooth(code))
        std::printf(" %s(k %g)", std::string(sdf_code_name(code)).c_str(), t.program_k[j]);
      else
        std::printf(" %s", std::string(sdf_code_name(code)).c_str());
    }
    Bounds3f bb = t.bounds(row);
    std::printf(", bounds (%g %g %g) to (%g %g %g)\n", bb.lo.x, bb.lo.y, bb.lo.z, bb.hi.x, bb.hi.y,
                bb.hi.z);
  }
}

// The environment and every texture: size, what render keeps of it and the most its reading
// holds, and why render would refuse it (a mesh file's texture: drop it). Returns how many
// `texture` and `environment` lines render would refuse.
int print_images(const SceneImageMemory& mem, const SceneImages& options) {
  if (mem.images.empty()) return 0;
  std::printf("images: %zu, %s of image memory to read them all; %s %s\n", mem.images.size(),
              bytes_text(mem.wanted).c_str(), bytes_text(options.memory).c_str(),
              options.chosen ? "given (--image-memory)" : "by default (half the memory available)");
  int refused = 0;
  for (const SceneImage& img : mem.images) {
    const bool of_mesh = img.kind == SceneImage::kMeshTexture;
    std::printf("  %-12s %u x %u, keeps %s, reading peaks at %s: %s\n",
                img.kind == SceneImage::kEnvironment ? "environment"
                : of_mesh                            ? "mesh texture"
                                                     : "texture",
                img.width, img.height, bytes_text(img.kept).c_str(), bytes_text(img.peak).c_str(),
                quote_path(img.file).c_str());
    if (img.refused.empty()) continue;
    if (!of_mesh) ++refused;
    std::printf("    warning: render %s it: %s\n", of_mesh ? "drops" : "refuses",
                img.refused.c_str());
  }
  return refused;
}

void print_materials(const Scene& s) {
  std::printf("materials: %zu\n", s.materials.size());
  for (std::size_t i = 0; i < s.materials.size(); ++i) {
    const Material& m = s.materials[i];
    if (m.is_light) {
      std::printf("  %2zu light  Le (%g %g %g)", i, m.emission.x, m.emission.y, m.emission.z);
    } else {
      std::printf("  %2zu brdf   Kd (%g %g %g) Ks (%g %g %g) alpha %g Kt (%g %g %g) ior %g", i,
                  m.kd.x, m.kd.y, m.kd.z, m.ks.x, m.ks.y, m.ks.z, m.alpha, m.kt.x, m.kt.y, m.kt.z,
                  m.ior);
    }
    if (m.microfacet != Microfacet::kPhong)
      std::printf(", microfacet %s", microfacet_name(m.microfacet));
    if (m.texture >= 0) std::printf(", texture %d", m.texture);
    if (m.mesh_copy_of >= 0) std::printf(" (material %d with its mesh's texture)", m.mesh_copy_of);
    std::printf("\n");
  }
}

const std::vector<OptionSpec> kInfoOptions = {
    {"lenient", 0, "", false, "skip bad scene lines with a warning instead of failing", ""},
    {"image-memory", 0, "MIB", false, kImageMemoryHelp, kImageMemoryDefault},
    {"set", 0, "LINE", true, kSetOptionHelp, ""},
};
const CommandHelp kInfoHelp{
    "raylane info [SCENE | MESH | FILM] [--lenient] [--set LINE]... [--image-memory MIB]",
    "Prints what raylane modelled from SCENE (default: the built-in course test scene): the\n"
    "screen and camera, the scene's bounds and each mesh's triangles and bounds, rows and bytes\n"
    "of each primitive table, materials, lights, the BVH (nodes, depth, SAH cost, bytes, build\n"
    "time) and the SIMD kernels this CPU runs. Given a mesh file (any format Assimp reads), it\n"
    "prints the mesh's triangles, the zero-area ones dropped, its bounds and the files read.\n"
    "Given a film (--checkpoint), its size, spp, seed, integrator, sampler and AOVs.",
    &kInfoOptions,
    "Textures and the environment are read to their headers only: their sizes, the bytes\n"
    "render keeps of each and the most its reading holds, with no pixel decoded, and a\n"
    "warning for each image render refuses at this --image-memory; info then exits with\n"
    "status 2, naming the --image-memory that reads them all."};

}  // namespace

void print_bounds(const char* label, const Bounds3f& b) {
  if (b.empty()) {
    std::printf("%s: empty\n", label);
    return;
  }
  std::printf("%s: (%g %g %g) to (%g %g %g)\n", label, b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y,
              b.hi.z);
}

void print_meshes(const std::vector<MeshSummary>& meshes) {
  for (const MeshSummary& m : meshes) {
    std::printf("mesh %s (line %d): %u triangles", quote_path(m.file).c_str(), m.loc.line,
                m.triangles);
    if (m.degenerate_dropped) std::printf(", %u zero-area dropped", m.degenerate_dropped);
    print_bounds(", bounds", m.bounds);
  }
}

// `raylane info MESH`: a mesh file on its own, as a `mesh` line with no placement reads it.
int info_mesh(const std::string& path) {
  TriangleTable table;
  auto stats = import_mesh_file(path, MeshPlacement{}, 0, table);
  if (!stats) {
    std::fprintf(stderr, "raylane: %s\n", stats.error().c_str());
    return kExitUsage;
  }
  Bounds3f b;
  for (uint32_t i = 0; i < table.size(); ++i)
    b.extend(table.bounds(i));
  std::printf("mesh: %s\n", quote_path(path).c_str());
  std::printf("triangles: %u (%u zero-area dropped)\n", stats->triangles,
              stats->degenerate_dropped);
  print_bounds("bounds", b);
  std::printf("files read:");
  for (const std::string& f : stats->files)
    std::printf(" %s", quote_path(f).c_str());
  std::printf("\n");
  return kExitOk;
}

int info_command(const std::vector<std::string>& args) {
  if (asks_for_help(args, kInfoOptions)) return print_help(kInfoHelp);
  auto parsed = parse_args(args, kInfoOptions);
  if (!parsed) return usage_error("info", parsed.error());
  if (parsed->positional.size() > 1)
    return usage_error("info", "info takes at most one scene file");
  std::optional<std::string> path;
  if (!parsed->positional.empty()) path = parsed->positional[0];
  if (path && mesh_extension_known(*path)) return info_mesh(*path);
  if (path && is_film_file(*path)) return info_film(*path);
  std::vector<std::string> overrides;
  if (parsed->has("set")) overrides = parsed->values.at("set");
  // Headers only: info says what a render would model without decoding a pixel.
  SceneImages images;
  images.headers_only = true;
  if (auto v = parsed->last("image-memory"))
    if (Status st = read_image_memory_option(*v, images.memory, images.chosen); !st)
      return usage_error("info", st.error());
  auto loaded = load_scene_for_cli(path, parsed->has("lenient"), false, overrides, images);
  if (!loaded) return kExitUsage;
  Scene& s = loaded->scene;
  std::printf("scene: %s\n", path ? path->c_str() : kBuiltinSceneName);
  std::printf("screen: %u x %u\n", s.width, s.height);
  const CameraSpec& c = *s.camera;
  std::printf("camera: eye (%g %g %g), ry %g\n", c.eye.x, c.eye.y, c.eye.z, c.ry);
  if (s.lens.radius > 0)
    std::printf("lens: aperture radius %g, in focus at %g\n", s.lens.radius, s.lens.focus);
  std::printf("ambient: (%g %g %g)\n", s.ambient.x, s.ambient.y, s.ambient.z);
  print_bounds("bounds", s.bounds());
  print_meshes(loaded->meshes);
  print_tables(s);
  print_csg_blocks(s);
  print_sdf_blocks(s);
  print_materials(s);
  int refused = print_images(loaded->images, images);
  std::printf("lights: %zu emitting primitives\n", s.lights.size());
  Bvh bvh = build_bvh_and_reorder(s, render_bvh_config(s));
  const BvhStats& b = bvh.stats;
  std::printf(
      "bvh: %u inner nodes, %u leaves, depth %u, SAH cost %.2f, %zu bytes, built in "
      "%.3f s\n",
      b.inner_nodes, b.leaves, b.depth, b.sah_cost, bvh.bytes(), b.build_seconds);
  if (bvh.wide.empty())
    std::printf("traversal: packets over the binary tree (wide nodes from %zu primitives on)\n",
                kWideNodesFrom);
  else
    std::printf("traversal: hybrid packets, single rays over 8-wide nodes (%zu bytes of them)\n",
                bvh.wide.bytes());
  std::printf("bvh leaf sizes:");
  for (std::size_t n = 1; n < b.leaf_size_histogram.size(); ++n)
    if (b.leaf_size_histogram[n]) std::printf(" %zu:%u", n, b.leaf_size_histogram[n]);
  std::printf("\npacket kernels: %s (%d lanes); this CPU has",
              std::string(isa_name(best_isa())).c_str(), isa_width(best_isa()));
  for (Isa isa : supported_isas())
    std::printf(" %s", std::string(isa_name(isa)).c_str());
  std::printf("\n");
  if (refused > 0 && !parsed->has("lenient")) {
    std::fprintf(
        stderr, "raylane: render refuses %s for image memory: --image-memory %llu reads %s\n",
        counted(refused, "image").c_str(),
        (unsigned long long)image_memory_mib(loaded->images.wanted), refused == 1 ? "it" : "them");
    return kExitUsage;
  }
  return kExitOk;
}

}  // namespace raylane::cli
