// Monte Carlo estimates with their standard error, for tests that compare an estimator with
// an analytic answer within a few σ.
#pragma once

#include <algorithm>
#include <cmath>

namespace raylane::testing {

struct Estimate {
  double mean = 0, sigma = 0;  // the mean and its standard error
};

// Mean and standard error of g() over n ≥ 2 draws.
template <class G>
Estimate estimate(int n, G&& g) {
  double s = 0, s2 = 0;
  for (int i = 0; i < n; ++i) {
    double v = g();
    s += v, s2 += v * v;
  }
  double mean = s / n, var = std::max(0.0, s2 / n - mean * mean);
  return {mean, std::sqrt(var / (n - 1))};
}

}  // namespace raylane::testing
