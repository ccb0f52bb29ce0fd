// Checks shared by the light tests: sentinels in a light batch's outputs, and the estimate of
// what a light shows by its samples against one by directions cast at it.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "raylane/core/ray.h"
#include "raylane/core/warps.h"
#include "raylane/render/lights/lights.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sampling.h"
#include "raylane/render/samplers/sobol.h"
#include "support/estimate.h"

namespace raylane::testing {

// Sentinels before each instruction set's run, so that a row one set's kernels skip cannot pass
// on the answer the set before left in the columns (every set's answers are the same bits).
// The cones' direction, distance and density NaN (no sample reads as valid), and the float
// directions `wi_float` (ConeBatch::wi_float's columns, if the test points them) -1.
inline void fill_light_sentinels(LightQueries& q,
                                 std::array<std::vector<float>, 3>* wi_float = nullptr) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t k = 0; k < 3; ++k) {
    std::fill(q.cones.wi[k].begin(), q.cones.wi[k].end(), nan);
    if (wi_float) std::fill((*wi_float)[k].begin(), (*wi_float)[k].end(), -1.0f);
  }
  std::fill(q.cones.dist.begin(), q.cones.dist.end(), nan);
  std::fill(q.cones.pdf.begin(), q.cones.pdf.end(), nan);
}

// Row i's radiance as the shading reads it (LightQueries::le_of: the one light's, or the row's).
inline glm::vec3 light_radiance(const LightQueries& q, std::size_t i) {
  const std::array<float, 3> le = q.le_of(i);
  return {le[0], le[1], le[2]};
}

// ∫ cos θ · [an emitting side of the light seen along ω] dω over the sphere of directions from
// `ref`, cos θ against `normal`: by the light's samples, cos / pdf (`draw(u_part, u1, u2)` one
// sample, with wi and pdf, from three float numbers), and by uniform directions cast at it,
// 4π · cos · [emits(ray)], 200,000 draws each. The two agree within 4 standard errors, and
// the light is seen (the cast estimate above `seen`).
template <class Draw, class Emits>
void expect_samples_estimate_what_the_light_shows(const glm::dvec3& ref, const glm::dvec3& normal,
                                                  Rng& rng, Draw draw, Emits emits, double seen) {
  const int count = 200000;
  const Estimate nee = estimate(count, [&] {
    const float u[3] = {unit_float(rng.uniform()), unit_float(rng.uniform()),
                        unit_float(rng.uniform())};
    const auto s = draw(u[0], u[1], u[2]);
    if (!(s.pdf > 0)) return 0.0;
    return std::abs(dot(glm::dvec3(s.wi), normal)) / double(s.pdf);
  });
  const Estimate cast = estimate(count, [&] {
    const glm::dvec3 w = sample_uniform_sphere(rng.uniform(), rng.uniform());
    const Rayd ray{ref, w, 0, std::numeric_limits<double>::infinity(), 0.5};
    return emits(ray) ? 4 * kPi * std::abs(dot(w, normal)) : 0.0;
  });
  EXPECT_GT(cast.mean, seen);
  EXPECT_NEAR(nee.mean, cast.mean, 4 * std::hypot(nee.sigma, cast.sigma));
}

}  // namespace raylane::testing
