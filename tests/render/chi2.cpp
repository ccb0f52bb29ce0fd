#include "chi2.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "raylane/render/samplers/sampling.h"

namespace raylane::testing {

namespace {

// Upper tail of χ² with k degrees of freedom (Wilson and Hilferty 1931).
double chi2_upper_tail(double x, int k) {
  double h = 2.0 / (9.0 * k);
  double z = (std::cbrt(x / k) - (1 - h)) / std::sqrt(h);
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

double cell_mass(const Frame& f, const DirectionPdf& pdf, double z0, double z1, double p0,
                 double p1) {
  constexpr int kSub = 24;
  double sum = 0, dz = (z1 - z0) / kSub, dp = (p1 - p0) / kSub;
  for (int i = 0; i < kSub; ++i)
    for (int j = 0; j < kSub; ++j) {
      double z = z0 + (i + 0.5) * dz, phi = p0 + (j + 0.5) * dp;
      double r = std::sqrt(std::max(0.0, 1 - z * z));
      sum += pdf(f.to_world({r * std::cos(phi), r * std::sin(phi), z}));
    }
  return sum * dz * dp;
}

}  // namespace

double sidak_level(double alpha, int tests) {
  return 1 - std::pow(1 - alpha, 1.0 / tests);
}

Chi2Result chi2_test(const Chi2Setup& s, const DirectionSampler& sample, const DirectionPdf& pdf,
                     uint64_t seed) {
  Frame frame(normalize(s.axis));
  const int cells = s.nz * s.nphi;
  const double zw = (1 - s.z_min) / s.nz, pw = 2 * kPi / s.nphi;
  std::vector<double> observed(cells + 2, 0.0), expected(cells + 2, 0.0);  // + outside, invalid
  Rng rng(seed);
  for (int n = 0; n < s.samples; ++n) {
    auto w = sample(rng);
    if (!w) {
      observed[cells + 1] += 1;
      continue;
    }
    glm::dvec3 l = frame.to_local(*w);
    if (l.z < s.z_min) {
      observed[cells] += 1;
      continue;
    }
    double phi = std::atan2(l.y, l.x);
    if (phi < 0) phi += 2 * kPi;
    int iz = std::min(s.nz - 1, int((l.z - s.z_min) / zw));
    int ip = std::min(s.nphi - 1, int(phi / pw));
    observed[iz * s.nphi + ip] += 1;
  }
  double total = 0;
  for (int iz = 0; iz < s.nz; ++iz)
    for (int ip = 0; ip < s.nphi; ++ip) {
      double z0 = s.z_min + iz * zw;
      double m = cell_mass(frame, pdf, z0, z0 + zw, ip * pw, (ip + 1) * pw);
      expected[iz * s.nphi + ip] = m * s.samples;
      total += m;
    }
  if (s.z_min > -1) {  // the rest of the sphere, on a grid of the same count
    double m = 0, ow = (s.z_min + 1) / s.nz;
    for (int iz = 0; iz < s.nz; ++iz)
      for (int ip = 0; ip < s.nphi; ++ip)
        m += cell_mass(frame, pdf, -1 + iz * ow, -1 + (iz + 1) * ow, ip * pw, (ip + 1) * pw);
    expected[cells] = m * s.samples;
    total += m;
  }
  expected[cells + 1] = std::max(0.0, 1 - total) * s.samples;

  Chi2Result r;
  std::vector<std::pair<double, double>> cells_eo;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (expected[i] == 0 && observed[i] > 1e-5 * s.samples) r.zero_cell_hit = true;
    cells_eo.push_back({expected[i], observed[i]});
  }
  std::sort(cells_eo.begin(), cells_eo.end());
  double pool_e = 0, pool_o = 0;
  int used = 0;
  for (auto [e, o] : cells_eo) {
    if (pool_e < 5) {  // pool the smallest cells until the pool expects at least 5
      pool_e += e, pool_o += o;
      if (pool_e >= 5) r.statistic += (pool_o - pool_e) * (pool_o - pool_e) / pool_e, ++used;
      continue;
    }
    r.statistic += (o - e) * (o - e) / e, ++used;
  }
  r.dof = used - 1;
  r.p_value = chi2_upper_tail(r.statistic, r.dof);
  return r;
}

}  // namespace raylane::testing
