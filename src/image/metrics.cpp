#include "raylane/image/metrics.h"

#include <cmath>
#include <limits>

namespace raylane {

Result<ImageDiff> compare(const Image& a, const Image& ref) {
  if (a.width != ref.width || a.height != ref.height) return Error{"images differ in size"};
  ImageDiff d;
  const std::size_t n = a.rgb.size();
  if (n == 0) return d;
  double se = 0, rel = 0, abs_sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(a.rgb[i]) || !std::isfinite(ref.rgb[i])) {
      ++d.nonfinite;
      continue;
    }
    double diff = double(a.rgb[i]) - ref.rgb[i];
    se += diff * diff;
    rel += diff * diff / (double(ref.rgb[i]) * ref.rgb[i] + 1e-2);
    abs_sum += std::abs(diff);
    if (std::abs(diff) > d.max_abs) {
      d.max_abs = std::abs(diff);
      d.max_x = uint32_t(i / 3 % a.width), d.max_y = uint32_t(i / 3 / a.width);
      d.max_channel = int(i % 3);
    }
  }
  d.rmse = std::sqrt(se / n);
  d.rel_mse = rel / n;
  d.mean_abs = abs_sum / n;
  if (d.nonfinite > 0) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    d.rmse = d.rel_mse = d.mean_abs = d.max_abs = kInf;
  }
  return d;
}

Image relative_error_map(const Image& a, const Image& ref) {
  Image out(a.width, a.height);
  const std::size_t pixels = std::size_t(a.width) * a.height;
  for (std::size_t p = 0; p < pixels; ++p) {
    double sum = 0;
    for (std::size_t c = 3 * p; c < 3 * p + 3; ++c) {
      double diff = double(a.rgb[c]) - ref.rgb[c];
      sum += diff * diff / (double(ref.rgb[c]) * ref.rgb[c] + 1e-2);
    }
    float e =
        std::isfinite(sum) ? float(std::sqrt(sum / 3)) : std::numeric_limits<float>::infinity();
    out.rgb[3 * p] = out.rgb[3 * p + 1] = out.rgb[3 * p + 2] = e;
  }
  return out;
}

glm::dvec3 mean(const Image& image) {
  glm::dvec3 sum{};
  std::size_t pixels = std::size_t(image.width) * image.height;
  for (std::size_t i = 0; i < pixels; ++i)
    sum += glm::dvec3(image.rgb[3 * i], image.rgb[3 * i + 1], image.rgb[3 * i + 2]);
  return pixels ? sum / double(pixels) : sum;
}

}  // namespace raylane
