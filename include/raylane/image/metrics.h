// Differences between images, for tests, convergence reports and `raylane diff`.
#pragma once

#include "raylane/core/error.h"
#include "raylane/image/image.h"

namespace raylane {

struct ImageDiff {
  double rmse = 0;      // sqrt(mean over channels of (a − r)²)
  double rel_mse = 0;   // mean over channels of (a − r)² / (r² + 1e-2)
  double mean_abs = 0;  // mean over channels of |a − r|
  double max_abs = 0;
  // Channels where either image is NaN or infinite: counted, not summed; any one makes the
  // images differ beyond every tolerance (the figures above are then +inf).
  uint64_t nonfinite = 0;
  // The pixel of the largest absolute difference (max_abs), top row first, and its channel.
  uint32_t max_x = 0, max_y = 0;
  int max_channel = 0;
};

// `ref` is the reference; the sizes must match. The 1e-2 in relMSE keeps dark pixels from
// dominating (the same guard as pbrt's imgtool MRSE).
Result<ImageDiff> compare(const Image& a, const Image& ref);
glm::dvec3 mean(const Image& image);

// Per-pixel relative error, for `raylane diff --heatmap` (as pbrt's `imgtool diff --difference`
// and FLIP's error maps are read): in every channel of a pixel, sqrt(mean over its channels of
// (a − r)² / (r² + 1e-2)), the term relMSE averages; non-finite pixels are +inf.
Image relative_error_map(const Image& a, const Image& ref);

}  // namespace raylane
