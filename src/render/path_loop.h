// The path tracer's render loop, shared by its files (include from src/render/path*.cpp only):
// a tile's paths and buffers, the context every step gets, and the steps one file hands
// another. path.cpp runs tiles and wavefronts, path_vertex.cpp shades vertices one by one in
// double (and holds what both shadings share), path_lanes.cpp shades a wavefront's vertices in
// lanes.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <vector>

#include "raylane/render/bsdf.h"
#include "raylane/render/lights.h"
#include "raylane/render/path.h"
#include "raylane/render/rng.h"
#include "raylane/render/shade_lanes.h"
#include "raylane/render/sobol.h"
#include "raylane/render/vertex_lanes.h"
#include "raylane/trace/ray_stream.h"

namespace raylane::path_detail {

inline constexpr uint32_t kTile = kPathTile;  // pixels per tile side: 256 paths per wavefront
inline constexpr uint32_t kBlock = 4;         // camera rays in 4×4 blocks: one coherent packet
inline constexpr double kRouletteSurvival = 0.8;

// A path between wavefronts. Its ray is not here: rays live in the thread's `rays`, row k
// for the path live[k], so that the wavefront's batch is already in order for the tracer.
struct PathState {
  Vec3d beta{1, 1, 1};  // throughput
  Vec3d radiance{0, 0, 0};
  Vec3d prev_p;                // the vertex the ray left (for the light pdf of MIS)
  double prev_pdf = 0;         // the BSDF density of the ray's direction
  bool prev_specular = false;  // ... drawn from a Dirac lobe: light sampling could not find it
  std::size_t pixel = 0;
  uint64_t pixel_seed = 0;  // the Sobol sampler's scramble of this pixel
};

// The shadow rays' queries, as columns (the lanes' write-back fills them in a filter pass): ray
// q, aimed at its light, is in the thread's shadow_rays; contribution[.][q] is added to path
// path[q]'s radiance if the light is the first thing it meets.
struct ShadowQueries {
  std::vector<uint32_t> path;
  std::array<std::vector<double>, 3> contribution;

  std::size_t size() const { return path.size(); }
  bool empty() const { return path.empty(); }
  void resize(std::size_t n) {
    path.resize(n);
    for (auto& c : contribution)
      c.resize(n);
  }
  void clear() { resize(0); }
  void push_back(uint32_t p, const Vec3d& c) {
    path.push_back(p);
    for (int k = 0; k < 3; ++k)
      contribution[std::size_t(k)].push_back(c[k]);
  }
  Vec3d contribution_of(std::size_t q) const {
    return {contribution[0][q], contribution[1][q], contribution[2][q]};
  }
  void swap(ShadowQueries& other) {
    path.swap(other.path);
    contribution.swap(other.contribution);
  }
};

// A phase timer that reads the clock only when the render asked for phase times.
class PhaseClock {
 public:
  explicit PhaseClock(bool on) : on_(on) {
    if (on_) last_ = std::chrono::steady_clock::now();
  }
  // Adds the time since the last lap to `into`.
  void lap(double& into) {
    if (!on_) return;
    auto now = std::chrono::steady_clock::now();
    into += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }

 private:
  bool on_;
  std::chrono::steady_clock::time_point last_;
};

// The vertices waiting for the lanes, as columns: row r is vertex r of the ShadeBatch and
// VertexBatch. Everything else about a row lives in those batches' columns (path_lanes.cpp
// fills them in a few passes).
struct LaneRows {
  std::vector<uint32_t> path;      // index into the tile's paths
  std::vector<uint32_t> hit;       // index into the wavefront's hits (and rays)
  std::vector<uint32_t> material;  // the hit's material row
  // From the hit's surface (Tracer::surfaces): dot(ns, d), and whether the ray met the front.
  std::vector<double> cos_ns;
  std::vector<uint8_t> front;

  void grow(std::size_t n) {
    if (path.size() >= n) return;
    path.resize(n), hit.resize(n), material.resize(n), cos_ns.resize(n), front.resize(n);
  }
};

// A thread's buffers, reused tile after tile: the render loop allocates nothing per sample
// once they have grown to a tile's size.
// Aligned to 128 bytes (a cache line and the one the adjacent-line prefetcher pairs with it):
// the threads' buffers sit side by side in one vector, and a wavefront's resizes write
// vector headers another thread would otherwise read its columns' pointers next to.
struct alignas(128) ThreadBuffers {
  std::vector<PathState> paths;
  std::vector<uint32_t> live, next_live;  // paths still going, by index
  // Ray k of `rays` is path live[k]'s, ray k of next_rays is next_live[k]'s: float columns, the
  // tracer's input as they are written. Shadow ray q belongs to queries[q] (next_queries while
  // a wavefront is shaded), its end column holds its light, blocked[q] is its answer.
  RayStream rays, next_rays, shadow_rays;
  ShadowQueries queries, next_queries;
  std::vector<Hit> hits;
  bool hits_have_surfaces = false;  // or prim and t alone (Tracer::closest's with_surface)
  std::vector<uint8_t> blocked;
  TraceScratch scratch;
  LaneRows lane_rows;  // rows [0, lane_count) are this wavefront's
  std::size_t lane_count = 0;
  ShadeBatch shade;
  SobolBatch sobol;
  LightQueries light_queries;  // row r's light group and light point, when lights are sampled
  VertexBatch vertices;
};

// What shading in lanes needs besides the settings (unused with Shading::kDouble).
struct LaneShading {
  const LaneMaterials& materials;
  Isa isa;
};

struct TileContext {
  ThreadBuffers& buffers;
  const Tracer& tracer;
  const LightSampler& lights;
  const PathSettings& settings;
  const LaneShading& lanes;
  Rng rng;
  PathStats stats;
  uint32_t light_calls;  // for timing one light sampling call in kLightTimingStride
  uint32_t pass;
};

// A path's decisions and the Sobol group each draws from (4 dimensions per group, the two
// that warp a direction or a point first, so that they get the (0, 2)-sequence's
// stratification). The MT19937 sampler ignores the groups and draws in call order.
struct Dims {
  static constexpr uint32_t camera = 0;  // (jitter x, jitter y, lens u1, lens u2)
  static uint32_t light(int depth) { return 1 + 2 * uint32_t(depth); }  // (u1, u2, light, part)
  static uint32_t bsdf(int depth) { return 2 + 2 * uint32_t(depth); }   // (u1, u2, lobe, roulette)
};

// A decision's numbers: the whole Sobol group at once, or, from MT19937, one number per
// component listed in `order`, drawn in that order (the order the course's code drew them).
inline std::array<double, 4> draw(TileContext& ctx, const PathState& p, uint32_t group,
                                  std::initializer_list<int> order) {
  if (ctx.settings.sampler == Sampler::kSobol) return sobol_group(p.pixel_seed, ctx.pass, group);
  std::array<double, 4> u{};
  for (int c : order)
    u[c] = ctx.rng.uniform();
  return u;
}

// path_vertex.cpp: what a vertex does with either shading.
bool samples_lights(const TileContext& ctx);
// Beer's law on a segment of length t that ends on a surface of a material (1 unless it ends
// on the inside of a transmissive solid).
Vec3d beer(const Material& m, bool front_face, double t);
// What the vertices of this depth follow: MIS or not, roulette or not.
VertexRules vertex_rules(const TileContext& ctx, int depth);
// Shades the wavefront's vertices: each live path's hit, in lanes where the settings and the
// material allow, one by one in double otherwise. Fills next_live, shadow_rays, next_queries.
void shade_wavefront(TileContext& ctx, int depth);

// path_lanes.cpp.
// Readies the lane batches for at most `most` vertices of this wavefront.
void start_lane_rows(TileContext& ctx, std::size_t most);
// A vertex for the lanes: path `path` at hit `hit_index` of the wavefront, on a material with
// in_lanes. shade_in_lanes fills its columns, the surface and Beer's law included (and drops
// it when nothing reflects there); the hit needs only prim and t.
inline void queue_lane_row(TileContext& ctx, uint32_t path, uint32_t hit_index, uint32_t material) {
  ThreadBuffers& b = ctx.buffers;
  const std::size_t r = b.lane_count++;
  b.lane_rows.path[r] = path, b.lane_rows.hit[r] = hit_index, b.lane_rows.material[r] = material;
}
// A path's ray as the tracer traced it: the stream's float ray, widened exactly.
inline Rayd ray_of(const RayStream& rays, std::size_t k) {
  return ray_cast<double>(rays.get(k));
}
// The queued vertices' columns, their BSDFs in one lane batch, then each vertex's shadow ray and
// next ray.
void shade_in_lanes(TileContext& ctx, int depth);

}  // namespace raylane::path_detail
