// The environment light's image-side math (docs/scene-language.md, "Equirectangular environment
// mapping"): the radiance s·E(d) an escaping ray sees, and importance sampling of directions
// ∝ luminance × sin θ with the matching solid-angle density, as pbrt-v4's ImageInfiniteLight
// and Cycles' background light do. The parser, the light sampler and the path tracer build on
// it; this module knows only the image, the scale and the orientation.
//
// Mapping (pbrt-v4's equirectangular convention, Z up): a point (u, v) ∈ [0, 1)² of the image,
// u from the left and v from the TOP, has φ = 2πu, θ = πv and the image-space direction
// (sin θ cos φ, sin θ sin φ, cos θ); the orientation R turns it into the world,
// d_world = R·d_image. The top row therefore looks along R·(0, 0, 1).
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "raylane/core/rotation.h"
#include "raylane/core/vec_math.h"
#include "raylane/core/warps.h"
#include "raylane/image/image.h"
#include "raylane/image/texels.h"

namespace raylane {

// Rec. 709 luminance of linear RGB (ITU-R BT.709 primaries, Y row).
inline double rec709_luminance(const glm::dvec3& rgb) {
  return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z;
}

// A piecewise-constant density over [0, 1) with n equal cells, sampled by inverting its CDF
// (PBRT 3rd ed. §13.3.1; pbrt-v4's PiecewiseConstant1D). The CDF is held in fixed point, as
// 32-bit counts of kUnits (2^31) units: 4 bytes a cell rather than a double CDF entry and a
// double weight (16), so that a large map's tables stay in the caches. A cell's density is its
// step in units, step·n / kUnits: the density the inversion samples, exactly, so that sample and
// pdf agree by construction. Cells of zero weight have no step and are never sampled; every
// other cell has a step of at least one unit, so that no light is left without density.
class PiecewiseConstant1D {
 public:
  PiecewiseConstant1D() = default;
  // f: the cells' weights, finite and ≥ 0 (negative values are taken as their magnitude); at
  // most kMaxCells of them (more are taken as zero weight).
  explicit PiecewiseConstant1D(std::vector<double> f);

  // x in [0, 1) with density pdf(x), found by inverting the CDF at u ∈ [0, 1) (1 is clamped
  // below 1). The cell and the density are returned as well; when the weights are all zero,
  // x = u and *pdf = 0 (nothing can be sampled; callers treat it as invalid).
  double sample_continuous(double u, double* pdf = nullptr, uint32_t* cell = nullptr) const;
  // The density at x: that of its cell; 0 outside [0, 1) or when integral() is 0.
  double pdf(double x) const;
  // The density of a whole cell (cell < size()): its step over the cells' mean step.
  double pdf_of_cell(uint32_t cell) const {
    return double(cdf_[cell + 1] - cdf_[cell]) * double(size()) * (1.0 / kUnits);
  }
  // ∫₀¹ f = Σ f / n of the weights as given (after abs), the 2-D marginal's weight of this row.
  double integral() const { return integral_; }
  uint32_t size() const { return cdf_.empty() ? 0 : uint32_t(cdf_.size() - 1); }
  // Asks the caches for the guide entry sample_continuous(u) reads first, and then, once that
  // has arrived, for the CDF entries it leads to: sample_many's rows, a few rows ahead.
  void prefetch_guide(double u) const { __builtin_prefetch(guide_.data() + guide_index(units(u))); }
  void prefetch_cell(uint32_t cell) const { __builtin_prefetch(cdf_.data() + cell); }
  void prefetch_cells(double u) const {
    if (guide_.empty()) return;
    __builtin_prefetch(cdf_.data() + guide_[guide_index(units(u))]);
  }
  // The memory the tables hold, for memory reports.
  std::size_t bytes() const {
    return cdf_.capacity() * sizeof(uint32_t) + guide_.capacity() * sizeof(uint32_t);
  }
  // The number of select steps a search of this table takes (the same for every u).
  uint32_t search_steps() const { return uint32_t(std::bit_width(first_step_)); }
  // The CDF's units: 2^31, so that the end fits a uint32_t and u·kUnits is exact.
  static constexpr uint32_t kUnits = uint32_t(1) << 31;
  // One guide entry per this many cells (what it adds a cell: 4 / this bytes).
  static constexpr uint32_t kCellsPerGuide = 4;
  // The most cells a table holds: every cell of weight > 0 needs a unit of its own.
  static constexpr uint32_t kMaxCells = uint32_t(1) << 28;

 private:
  // u ∈ [0, 1) in units, rounded down: below kUnits.
  static uint32_t units(double u) {
    return u >= 0 ? uint32_t(std::min(u, 0x1.fffffffffffffp-1) * kUnits) : 0;  // NaN: 0
  }
  // The guide entry below U units (0 without a guide table): exact in integers, so U always
  // lies within the entry's span.
  uint32_t guide_index(uint32_t units) const {
    const std::size_t g = guide_.size();
    return g < 2 ? 0 : uint32_t((uint64_t(units) * (g - 1)) >> 31);
  }
  // The cell i with cdf[i] ≤ U < cdf[i + 1], searching cells [lo, hi] only.
  uint32_t cell_within(uint32_t units, uint32_t lo, uint32_t hi) const;
  void build_guide();

  // n + 1 running sums in units, from 0 to exactly kUnits (all 0 when integral_ is 0).
  std::vector<uint32_t> cdf_;
  // The guide table (Chen and Asau 1974, "On generating random variates from an empirical
  // distribution"; Devroye 1986, §III.2.4): entry k is the cell that holds the first unit of
  // span k of g equal spans, so that the search for u's cell runs over the few cells between
  // two entries rather than all n: the same cell as a search of the whole CDF, at a quarter of
  // a word per cell.
  std::vector<uint32_t> guide_;
  uint32_t first_step_ = 0;  // the largest power of two ≤ the longest span, hi − lo
  double integral_ = 0;
};

// A piecewise-constant density over [0, 1)² on an nu × nv grid: v drawn from the marginal
// over rows, then u from that row's conditional (pbrt-v4's PiecewiseConstant2D; PBRT 3rd ed.
// §13.6.7). The joint density of a cell is its row's density in the marginal times its own in
// the row's conditional: f(u, v) / ∫∫f, up to the tables' units.
class PiecewiseConstant2D {
 public:
  struct Sample {
    double u = 0, v = 0;  // the point in [0, 1)²
    double pdf = 0;       // its density in (u, v) measure; 0 = invalid
    uint32_t cell_u = 0, cell_v = 0;
  };

  PiecewiseConstant2D() = default;
  // f: nu·nv weights, row-major (f[iv·nu + iu]), finite and ≥ 0.
  PiecewiseConstant2D(const std::vector<double>& f, uint32_t nu, uint32_t nv);
  // The same, each row's nu weights written by fill(iv, row) in turn, so that no nu·nv array
  // of weights is held besides the tables.
  PiecewiseConstant2D(uint32_t nu, uint32_t nv,
                      const std::function<void(uint32_t, std::vector<double>&)>& fill);

  // u2 picks the row (marginal), u1 the column within it (conditional).
  Sample sample(double u1, double u2) const;
  // sample(u1[i], u2[i]) into out[i] for i < n: every row's marginal, then every row's
  // conditional, so that the table reads of many rows overlap (one row's chain of dependent
  // loads left the processor waiting on memory).
  void sample_many(std::size_t n, const double* u1, const double* u2, Sample* out) const;
  // The density sample() has at (u, v); 0 outside [0, 1)².
  double pdf(double u, double v) const;
  // Asks the caches for the CDF entries pdf(u, v) reads (u, v ∈ [0, 1)).
  void prefetch_pdf(double u, double v) const;
  // ∫∫ f over [0, 1)²: 0 means nothing can be sampled.
  double integral() const { return marginal_.integral(); }
  std::size_t bytes() const;

 private:
  double pdf_of_cells(uint32_t iu, uint32_t iv) const;  // the density of one cell

  std::vector<PiecewiseConstant1D> conditional_;  // one per row, over u
  PiecewiseConstant1D marginal_;                  // over v, weights = the rows' integrals
};

struct EnvironmentSample {
  glm::dvec3 wi{};  // unit world direction toward the environment
  glm::dvec3 le{};  // the radiance s·E(wi) arriving along −wi
  double pdf = 0;   // solid-angle density; 0 = invalid (black map, or a pole)
  bool valid() const { return pdf > 0; }
};

// Many rows' numbers and samples (EnvironmentMap::sample_many), reused between calls.
struct EnvironmentBatch {
  std::vector<double> u1, u2;
  std::vector<PiecewiseConstant2D::Sample> uv;
  std::vector<EnvironmentSample> out;
  void resize(std::size_t n) { u1.resize(n), u2.resize(n), uv.resize(n), out.resize(n); }
};

struct EnvironmentSeenBatch;

class EnvironmentMap {
 public:
  // image: linear RGB, top row first, at least 1×1, every value finite and ≥ 0 (the image
  // reader checks that); scale s > 0; rotation R, orthonormal (an orientation's matrix).
  // Total all the same, so no input can put a NaN into a render: an empty image, or one whose
  // buffer does not match its size, becomes a black 1×1 map; a negative or non-finite texel
  // becomes 0; a scale that is not finite and > 0 makes the map black.
  EnvironmentMap(Image image, double scale, const glm::dmat3& rotation);
  // The scene's texels, shared rather than copied; a null, empty or mis-sized one becomes a
  // black 1×1 map as above (the image reader has checked the texels' values).
  EnvironmentMap(std::shared_ptr<const TexelImage> texels, double scale,
                 const glm::dmat3& rotation);

  // s·E(d) for a ray leaving the scene along dir_world (any length > 0): bilinear between
  // texel centres, repeating in u (across φ = 0) and clamped in v (at the poles), as the
  // scene language's textures filter.
  glm::dvec3 radiance(const glm::dvec3& dir_world) const;
  // radiance(dir_world) and pdf(dir_world) at once, the direction turned into the image's
  // coordinates once (its arc tangents and square roots were half an escaped ray's cost).
  struct Seen {
    glm::dvec3 le{};
    double pdf = 0;
  };
  Seen seen(const glm::dvec3& dir_world) const;
  // seen() for each of the batch's directions (its dir into its seen), the same answers: every
  // direction's image point first, then the lookups with the texels of rows a few ahead
  // prefetched (one escaped ray at a time waited on its texels' lines).
  void seen_many(EnvironmentSeenBatch& b) const;
  // s·E at image coordinates (u, v) ∈ [0, 1)²: the same filter, without the direction.
  glm::dvec3 radiance_uv(double u, double v) const;

  // The image point (u, v) of an image-space direction, and its sin θ (0 at the poles or for
  // a zero vector).
  struct ImagePoint {
    double u = 0, v = 0, sin_theta = 0;
  };

  // A direction drawn ∝ luminance × sin θ (piecewise constant over the pixels) from u1, u2 ∈
  // [0, 1): pdf = pdf_uv / (2π² sin θ), the Jacobian of (u, v) ↦ direction being
  // dω = sin θ dθ dφ = 2π² sin θ du dv (PBRT 3rd ed. §14.2.4). Invalid (pdf 0) when the map
  // is black or the point falls exactly on a pole (sin θ = 0).
  EnvironmentSample sample(double u1, double u2) const;
  // sample() for each of the batch's rows (its u1, u2 into its out), the same answers; the
  // tables are read a stage at a time across the rows.
  void sample_many(EnvironmentBatch& b) const;
  // The density sample() has for dir_world (any length > 0), for MIS weights: 0 when the map
  // is black, at the poles, or for a zero vector.
  double pdf(const glm::dvec3& dir_world) const;
  // False when the map is black: sample() is then always invalid and pdf() always 0.
  bool can_sample() const { return distribution_.integral() > 0; }

  // The flux the environment sends through a disc of the scene's bounding radius r,
  // Φ = π r² · ∫ s·lum(E(ω)) dω (pbrt-v4's ImageInfiniteLight::Phi), for choosing lights by
  // power. Luminance with Rec. 709 weights; the integral is the bilinear map's, in closed
  // form (environment.cpp, luminance_sphere_integral). 0 for a black map.
  double power_estimate(double scene_radius) const;
  // The mean of s·lum(E) over the sphere, ∫ s·lum(E) dω / 4π.
  double average_luminance() const { return luminance_integral_ / (4 * kPi); }

  uint32_t width() const { return texels_->width; }
  uint32_t height() const { return texels_->height; }
  const TexelImage& texels() const { return *texels_; }
  double scale() const { return scale_; }
  const glm::dmat3& rotation() const { return rotation_; }
  // Memory held: the texels (shared with the scene) and the sampling tables.
  std::size_t bytes() const;

 private:
  static ImagePoint to_image_point(const glm::dvec3& d_image);
  double pdf_at(const ImagePoint& p) const;              // pdf() of a direction's image point
  glm::dvec3 to_image(const glm::dvec3& d_world) const;  // Rᵀ·d: R is orthonormal
  glm::dvec3 texel(uint32_t x, uint32_t y) const;        // unscaled RGB in double
  // The direction, radiance and solid-angle density of a point the distribution sampled.
  void direction_of(const PiecewiseConstant2D::Sample& uv, EnvironmentSample& s) const;
  void prefetch_texels(double u, double v) const;  // sample_many's and seen_many's rows ahead
  void build_distribution();
  // ∫ lum(E) dω over the sphere (unscaled), from the rows' mean luminances.
  double luminance_sphere_integral(const std::vector<double>& row_mean) const;

  std::shared_ptr<const TexelImage> texels_;
  double scale_;
  glm::dmat3 rotation_{1.0};
  PiecewiseConstant2D distribution_;  // ∝ cell-average luminance × sin θ of the row centre
  double luminance_integral_ = 0;     // ∫ s·lum(E) dω
};

// Many escaped rays' directions and what they see (EnvironmentMap::seen_many), reused between
// calls.
struct EnvironmentSeenBatch {
  std::vector<glm::dvec3> dir;
  std::vector<EnvironmentMap::ImagePoint> point;  // seen_many's scratch
  std::vector<EnvironmentMap::Seen> seen;
};

}  // namespace raylane
