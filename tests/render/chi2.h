// A chi-square goodness-of-fit test of a direction sampler against its density, after the
// setups of pbrt-v4 (src/pbrt/bsdfs_test.cpp) and Mitsuba 3 (chi2.py), see docs/hard-cases.md M4:
// directions binned in (z, φ) around an axis (z = cos of the angle to it, so a cell's solid
// angle is Δz·Δφ), expected counts from the density integrated over each cell (24×24 midpoint
// sub-samples), cells below 5 expected pooled, a cell for samples outside the binned cap
// and one for invalid samples (expected N·(1 − ∫pdf)). The p-value uses the Wilson–Hilferty
// normal approximation of the χ² distribution (accurate to ~1e-3 for the hundreds of degrees
// of freedom used here).
#pragma once

#include <functional>
#include <optional>

#include "raylane/core/vec_math.h"
#include "raylane/render/samplers/rng.h"

namespace raylane::testing {

struct Chi2Setup {
  glm::dvec3 axis{0, 0, 1};
  double z_min = -1;  // the binned cap is z in [z_min, 1]
  int nz = 50, nphi = 100;
  int samples = 1'000'000;
};

struct Chi2Result {
  double p_value = 0;
  double statistic = 0;
  int dof = 0;
  bool zero_cell_hit = false;  // samples where the density is 0
};

using DirectionSampler = std::function<std::optional<glm::dvec3>(Rng&)>;  // nullopt = invalid
using DirectionPdf = std::function<double(const glm::dvec3&)>;

Chi2Result chi2_test(const Chi2Setup& setup, const DirectionSampler& sample,
                     const DirectionPdf& pdf, uint64_t seed);

// Šidák's correction: the per-test level that keeps the family's false-alarm rate at alpha.
double sidak_level(double alpha, int tests);

}  // namespace raylane::testing
