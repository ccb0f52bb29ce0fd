// Sentinels in a light batch's outputs before each instruction set's run, so that a row one
// set's kernels skip cannot pass on the answer the set before left in the columns (every set's
// answers are the same bits).
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "raylane/render/lights/lights.h"

namespace raylane::testing {

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

}  // namespace raylane::testing
