// What every stage of the path tracer's wavefront gets (include from src/render only): the
// tracer, lights and settings, the thread's wavefront, its random numbers and statistics.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <initializer_list>

#include "raylane/render/lights/lights.h"
#include "raylane/render/materials/shade_lanes.h"
#include "raylane/render/path.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sobol.h"
#include "raylane/render/vertex_lanes.h"
#include "render/render_lanes.h"
#include "render/wavefront/queues.h"

namespace raylane::path_detail {

inline constexpr uint32_t kTile = kPathTile;  // pixels per tile side: 256 paths per tile
inline constexpr uint32_t kBlock = 4;         // camera rays in 4×4 blocks: one coherent packet
inline constexpr double kRouletteSurvival = 0.8;

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

// What shading in lanes needs besides the settings (with Shading::kDouble, only the
// materials' routes are read: LaneMaterials::route): the materials, the instruction set, and
// its table of render kernels, looked up once for the render (src/render/render_lanes.h).
struct LaneShading {
  const LaneMaterials& materials;
  Isa isa;
  const detail::RenderLanes& kernels;
};

// One render thread's state for a pass: it lives across the tiles the thread claims (their
// paths share its wavefront), so it is named for the thread, not for a tile.
struct ThreadContext {
  Wavefront& wave;
  const Tracer& tracer;
  const LightSampler& lights;
  const PathSettings& settings;
  const LaneShading& lanes;
  Rng rng;
  PathStats stats;
  uint32_t light_calls;  // for timing one light sampling call in a stride of them
  uint32_t pass;
};

// Whether the vertices sample lights (next-event estimation).
inline bool samples_lights(const ThreadContext& ctx) {
  return ctx.settings.integrator != Integrator::kBrdf && !ctx.lights.empty();
}

// Whether a vertex at this depth plays Russian roulette (from bounce rr_depth on).
inline bool has_roulette(int rr_depth, uint32_t depth) {
  return int(depth) + 1 >= rr_depth;
}

// What the vertices of this depth follow: MIS or not, roulette or not.
inline VertexRules vertex_rules(const ThreadContext& ctx, uint32_t depth) {
  return {ctx.settings.integrator == Integrator::kMis, has_roulette(ctx.settings.rr_depth, depth),
          kRouletteSurvival};
}

// A path's decisions and the Sobol group each draws from (4 dimensions per group, the two
// that warp a direction or a point first, so that they get the (0, 2)-sequence's
// stratification). The MT19937 sampler ignores the groups and draws in call order.
struct Dims {
  static constexpr uint32_t camera = 0;  // (jitter x, jitter y, lens u1, lens u2)
  // The Sobol group of the light sample at a depth: (u1, u2, light, part).
  static uint32_t light_group(uint32_t depth) { return 1 + 2 * depth; }
  // The Sobol group of the BSDF sample at a depth: (u1, u2, lobe, roulette).
  static uint32_t bsdf_group(uint32_t depth) { return 2 + 2 * depth; }
  // The Sobol group of a path's time, component 0 (motion blur only): one group of its own,
  // beyond every depth's, so that a scene that moves draws the other groups as one that does
  // not.
  static constexpr uint32_t time = ~0u;
};

// The order in which MT19937 draws a group's components (the order the course's code drew
// them): the light's choice first, then its point; the lobe first, then the direction.
inline constexpr std::initializer_list<int> kLightDrawOrder = {2, 3, 0, 1};
inline constexpr std::initializer_list<int> kBsdfDrawOrder = {2, 0, 1};

// A decision's numbers: the whole Sobol group at once, or, from MT19937, one number per
// component listed in `order`, drawn in that order.
inline std::array<double, 4> draw(ThreadContext& ctx, const PathState& p, uint32_t group,
                                  std::initializer_list<int> order) {
  if (ctx.settings.sampler == Sampler::kSobol) return sobol_group(p.pixel_seed, ctx.pass, group);
  std::array<double, 4> u{};
  for (int c : order)
    u[std::size_t(c)] = ctx.rng.uniform();
  return u;
}

// A path's ray as the tracer traced it: the stream's float ray, widened exactly.
inline Rayd ray_of(const RayStream& rays, std::size_t k) {
  return ray_cast<double>(rays.get(k));
}

}  // namespace raylane::path_detail
