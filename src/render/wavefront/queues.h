// The path tracer's wavefront (include from src/render only): a tile's paths and the queues
// its stages hand each other, named by purpose as pbrt-v4's wavefront integrator names its
// queues (Pharr, Jakob, Humphreys, "Physically Based Rendering", 4th ed., ch. 15). The stages
// themselves are listed in render/wavefront/stages.h, and run in that order by path.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "raylane/core/column.h"
#include "raylane/core/vec_math.h"
#include "raylane/render/lights/lights.h"
#include "raylane/render/materials/shade_lanes.h"
#include "raylane/render/samplers/sobol.h"
#include "raylane/render/vertex_lanes.h"
#include "raylane/trace/ray_stream.h"
#include "raylane/trace/tracer.h"

namespace raylane::path_detail {

// A path between wavefronts: what stays with its pixel. What changes from bounce to bounce
// travels with its ray (PathCarry).
struct PathState {
  uint64_t pixel_seed = 0;  // the Sobol sampler's scramble of this pixel
  glm::dvec3 radiance{0, 0, 0};
  std::size_t pixel = 0;
};

// What a path carries to the vertex its ray arrives at, one ray's worth (PathCarry holds it
// as columns).
struct Carried {
  glm::dvec3 beta{1, 1, 1};  // throughput
  double prev_pdf = 0;       // the BSDF density of the ray's direction
  // The vertex the ray left, for the light's density in an emitter's MIS weight: the lanes'
  // float point as it is; the double shading's rounded to float (a relative change of 2^-24 in
  // a point that only weighs the emission, far below the density's own roundoff).
  glm::vec3 prev_p{};
  // The depth the ray arrives at: 0 for the camera ray, one more at every vertex that sends the
  // path on. A wavefront that refills holds paths of different depths side by side.
  uint32_t depth = 0;
  bool prev_specular = false;  // drawn from a Dirac lobe: light sampling could not find what
                               // the ray meets
};

// The paths' state carried by their rays, as columns beside the rays (pbrt-v4's wavefront
// integrator carries each path's depth, throughput and previous vertex in its ray queue's
// items the same way: Pharr, Jakob, Humphreys, 4th ed., §15.2). The stages read it in ray
// order, and the scatter kernel packs it with the next rays it makes; a record per path would
// be read and written at the paths' scattered slots instead.
struct PathCarry {
  std::array<Column<double>, 3> beta;
  Column<double> prev_pdf;
  std::array<Column<float>, 3> prev_p;
  Column<uint32_t> depth;
  Column<uint8_t> prev_specular;

  template <class F>
  void for_each_column(F f) {
    for (auto& c : beta)
      f(c);
    f(prev_pdf);
    for (auto& c : prev_p)
      f(c);
    f(depth), f(prev_specular);
  }
  void resize(std::size_t n) {
    for_each_column([n](auto& c) { c.resize(n); });
  }
  Carried get(std::size_t k) const {
    Carried c;
    c.beta = {beta[0][k], beta[1][k], beta[2][k]}, c.prev_pdf = prev_pdf[k];
    c.prev_p = {prev_p[0][k], prev_p[1][k], prev_p[2][k]};
    c.depth = depth[k], c.prev_specular = prev_specular[k] != 0;
    return c;
  }
  void set(std::size_t k, const Carried& c) {
    for (int j = 0; j < 3; ++j)
      beta[std::size_t(j)][k] = c.beta[j], prev_p[std::size_t(j)][k] = c.prev_p[j];
    prev_pdf[k] = c.prev_pdf, depth[k] = c.depth, prev_specular[k] = c.prev_specular ? 1 : 0;
  }
  // Rows [at, at + n) set to c.
  void fill(std::size_t at, std::size_t n, const Carried& c) {
    auto to = [&](auto& col, auto v) { std::fill_n(col.begin() + std::ptrdiff_t(at), n, v); };
    for (std::size_t j = 0; j < 3; ++j)
      to(beta[j], c.beta[int(j)]), to(prev_p[j], c.prev_p[int(j)]);
    to(prev_pdf, c.prev_pdf), to(depth, c.depth), to(prev_specular, uint8_t(c.prev_specular));
  }
  void swap(PathCarry& other) {
    beta.swap(other.beta), prev_pdf.swap(other.prev_pdf), prev_p.swap(other.prev_p);
    depth.swap(other.depth), prev_specular.swap(other.prev_specular);
  }
};

// Rays to trace, in the float columns the tracer reads: ray k is path[k]'s, and carries its
// state (carry, row k).
struct RayQueue {
  Column<uint32_t> path;  // index into the wavefront's paths
  RayStream rays;
  PathCarry carry;

  std::size_t size() const { return path.size(); }
  bool empty() const { return path.empty(); }
  void clear() { path.clear(), rays.clear(), carry.resize(0); }
  void swap(RayQueue& other) {
    path.swap(other.path), std::swap(rays, other.rays), carry.swap(other.carry);
  }
  // One more ray, path p's, carrying c.
  void push(uint32_t p, const Rayf& ray, const Carried& c) {
    const std::size_t k = size();
    path.push_back(p);
    RayAppender(rays, 1, false).push(ray);
    carry.resize(k + 1), carry.set(k, c);
  }
  // The rays of `other` after these (their tmin, tmax, paths and state; no aims or times: a
  // stream of camera and bounce rays has neither before stamp_times).
  void append(const RayQueue& other) {
    const std::size_t at = size(), n = other.size();
    path.resize(at + n), rays.resize(at + n), carry.resize(at + n);
    std::copy_n(other.path.begin(), n, path.begin() + std::ptrdiff_t(at));
    const RayStream& o = other.rays;
    for (auto c : {&RayStream::ox, &RayStream::oy, &RayStream::oz, &RayStream::dx, &RayStream::dy,
                   &RayStream::dz, &RayStream::tmin, &RayStream::tmax})
      std::copy_n((o.*c).begin(), n, (rays.*c).begin() + std::ptrdiff_t(at));
    append_carry(other.carry, at, n);
  }

 private:
  void append_carry(const PathCarry& o, std::size_t at, std::size_t n) {
    auto copy = [&](const auto& from, auto& to) {
      std::copy_n(from.begin(), n, to.begin() + std::ptrdiff_t(at));
    };
    for (std::size_t j = 0; j < 3; ++j)
      copy(o.beta[j], carry.beta[j]), copy(o.prev_p[j], carry.prev_p[j]);
    copy(o.prev_pdf, carry.prev_pdf), copy(o.depth, carry.depth);
    copy(o.prev_specular, carry.prev_specular);
  }
};

// Shadow rays, each aimed at its light (the stream's aim column), and what each adds to its
// path if the light is the first thing it meets: contribution[.][q] to path[q]'s radiance.
struct ShadowQueue {
  RayStream rays;
  Column<uint32_t> path;
  std::array<Column<double>, 3> contribution;

  std::size_t size() const { return path.size(); }
  bool empty() const { return path.empty(); }
  // The query columns (the rays are sized by whoever writes them).
  void resize_queries(std::size_t n) {
    path.resize(n);
    for (auto& c : contribution)
      c.resize(n);
  }
  void clear() { rays.clear(), resize_queries(0); }
  void push_back(uint32_t p, const glm::dvec3& c) {
    path.push_back(p);
    for (int k = 0; k < 3; ++k)
      contribution[std::size_t(k)].push_back(c[k]);
  }
  glm::dvec3 contribution_of(std::size_t q) const {
    return {contribution[0][q], contribution[1][q], contribution[2][q]};
  }
  void swap(ShadowQueue& other) {
    std::swap(rays, other.rays), path.swap(other.path), contribution.swap(other.contribution);
  }
};

// The tile's pixel points for its camera rays: path i's pixel corner (x[i], y[i]) in the
// pixel grid (y up from the bottom edge) and its jitter (jx[i], jy[i]).
struct CameraPoints {
  std::vector<double> x, y, jx, jy;
  void resize(std::size_t n) { x.resize(n), y.resize(n), jx.resize(n), jy.resize(n); }
};

// Hits on a material shaded one by one in double: ray k of the wavefront, its material row.
struct DoubleVertexQueue {
  std::vector<uint32_t> ray, material;
  void clear() { ray.clear(), material.clear(); }
  void push(uint32_t k, uint32_t m) { ray.push_back(k), material.push_back(m); }
};

// Hits on a material shaded in lanes, as columns: row r is vertex r of every batch below
// (sort_arrivals fills what it reads of the path, the shading stage the rest in a few passes).
// Rows [0, count) are this wavefront's; the columns only grow.
struct LaneVertexQueue {
  std::size_t count = 0;
  std::vector<uint32_t> path;      // index into the wavefront's paths
  std::vector<uint32_t> ray;       // index into the wavefront's rays and hits
  std::vector<uint32_t> material;  // the hit's material row
  std::vector<uint32_t> depth;     // the vertex's depth (its Sobol groups, its roulette)
  // The Sobol seeds of the row's light and BSDF groups: its path's PathState::pixel_seed salted
  // by the group of the row's depth (sobol.h, group_salt), so that one call for group 0 draws
  // every row's own group. Made as the row is queued (the path is at hand then).
  std::vector<uint64_t> light_seed, bsdf_seed;
  // Some row plays Russian roulette (VertexBatch::survival). Set as the rows are queued, so it
  // may stay true after drop_black_rows drops every such row: roulette's numbers are then drawn
  // for rows that survive anyway (survival 1), the images the same.
  bool any_roulette = false;
  // From the hit's surface (Tracer::surfaces): dot(ns, d), and whether the ray met the front.
  std::vector<double> cos_ns;
  std::vector<uint8_t> front;
  ShadeBatch shade;            // the BSDF's float lanes
  SobolBatch sobol;            // the rows' Sobol scrambles and numbers
  LightQueries light_queries;  // light group numbers and light points, when lights are sampled
  VertexBatch vertices;        // the scatter kernel's vertices: shadow rays, next rays

  // Room for n rows, padded to 16 as the batches are (the scatter kernel reads `path` in whole
  // registers).
  void grow(std::size_t n) {
    n = (n + 15) / 16 * 16;
    if (path.size() >= n) return;
    path.resize(n), ray.resize(n), material.resize(n), depth.resize(n), cos_ns.resize(n);
    front.resize(n), light_seed.resize(n), bsdf_seed.resize(n);
  }
};

// A tile whose paths are in a wavefront: path slots [first, first + paths) of its `paths`.
struct TileInFlight {
  std::ptrdiff_t tile = -1;  // -1: a free block of slots
  uint32_t first = 0, paths = 0;
  uint32_t live = 0;   // rays and shadow rays of its paths waiting (or 1 for any: finish_tiles)
  double seconds = 0;  // its share of the thread's CPU time (MPI's tile costs)
};

// A thread's wavefront, reused tile after tile: the render loop allocates nothing per sample
// once its queues have grown. Each step traces `rays` and `shadows` (the shadow rays of the
// vertices before), then its stages sort the hits into `double_vertices` and `lane_vertices`
// (escaped rays and emitters are finished as they are sorted), and shading fills `next_rays`
// and `next_shadows`. With the Sobol sampler the wavefront refills: when its rays run low, the
// next tile's camera rays join the paths still going (path.cpp), so the paths of a step may be
// at any depth, each its own (the depth its ray carries: PathCarry::depth).
// Aligned to 128 bytes (a cache line and the one the adjacent-line prefetcher pairs with it):
// the threads' wavefronts sit side by side in one vector, and a queue's resizes write vector
// headers another thread would otherwise read its columns' pointers next to.
struct alignas(128) Wavefront {
  std::vector<PathState> paths;
  // Motion blur only: path i's instant in the shutter interval, drawn with its camera sample
  // and carried by every ray of the path (stamp_times). Empty for a scene that does not move.
  std::vector<float> path_time;
  CameraPoints camera;
  RayQueue rays, next_rays;
  ShadowQueue shadows, next_shadows;
  // Ray k's hit as columns: its primitive (hits.prim[k], invalid for a miss) and t. What the
  // stages read of most hits; the lane rows' surfaces come from them (Tracer::surfaces).
  HitStream hits;
  // Ray k's hit with its surface, in a step that reads every surface (the double shading, the
  // camera AOVs, a reference tracer); empty otherwise.
  std::vector<Hit> records;
  std::vector<uint8_t> blocked;  // blocked[q] for shadow ray q
  DoubleVertexQueue double_vertices;
  LaneVertexQueue lane_vertices;
  // The rays that left the scene under an environment (this step), and what they see: looked
  // up together after the hits are sorted.
  std::vector<uint32_t> escaped;
  // The rays whose arrival scalar code finishes (sort_arrival_rows' rare rows).
  std::vector<uint32_t> rare_arrivals;
  EnvironmentSeenBatch escapes;
  TraceScratch scratch;
  std::vector<TileInFlight> tiles;  // block b holds paths [b·kTile², (b + 1)·kTile²)
  std::size_t camera_rays = 0;      // rays [0, camera_rays) of `rays` are camera rays (this step)

  // Ray k's hit with its surface: its record, or its columns completed for `ray`.
  Hit record(std::size_t k, const Tracer& tracer, const Rayd& ray) const {
    if (!records.empty()) return records[k];
    Hit h;
    h.t = hits.t[k], h.prim = PrimRef::from_bits(hits.prim[k]);
    tracer.complete(ray, h);
    return h;
  }
};

}  // namespace raylane::path_detail
