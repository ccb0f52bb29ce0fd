#include "raylane/render/lights/environment.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <utility>

#include "raylane/core/fast_math.h"
#include "raylane/render/materials/texel_lookup.h"

namespace raylane {

namespace {

// The largest double below 1: where an x or u that rounded up to 1 is put back into [0, 1).
constexpr double kOneMinusEpsilon = 0x1.fffffffffffffp-1;

// The weights of a texel and its two neighbours in the average of the linear interpolation
// (between texel centres) over one cell: on the cell's left half the cell's own texel weighs
// 1/2…1 against its left neighbour, 3/4 on average; the same on the right half.
constexpr double kSide = 1.0 / 8, kCentre = 3.0 / 4;

uint32_t wrap(int64_t i, uint32_t n) {
  int64_t m = i % int64_t(n);
  return uint32_t(m < 0 ? m + n : m);
}

// ∫ m(v)·2π² sin(πv) dv over [va, vb] for m linear from ma at va to mb at vb, in closed form:
// ∫ sin(πv) dv = −cos(πv)/π and ∫ v sin(πv) dv = (sin(πv) − πv cos(πv))/π².
double band_integral(double va, double vb, double ma, double mb) {
  if (!(vb > va)) return 0;
  double slope = (mb - ma) / (vb - va), offset = ma - slope * va;
  auto antiderivative = [&](double v) {
    double c = std::cos(kPi * v), s = std::sin(kPi * v);
    return -2 * kPi * offset * c + 2 * slope * (s - kPi * v * c);
  };
  return antiderivative(vb) - antiderivative(va);
}

// The image as the constructor's contract promises it: a size that matches the buffer, at
// least 1×1, texels finite and ≥ 0.
Image sanitized(Image image) {
  if (image.width == 0 || image.height == 0 ||
      image.rgb.size() != std::size_t(image.width) * image.height * 3)
    return Image(1, 1);
  for (float& c : image.rgb)
    if (!(c >= 0 && std::isfinite(c))) c = 0;
  return image;
}

// The cell of x ∈ [0, 1) among n, against the same edges k/n (rounded) that sampling keeps x
// between: x·n alone may round across an edge.
// A scene's texels as the constructor takes them: present, at least 1×1, with the buffer its
// format and size need.
bool usable(const std::shared_ptr<const TexelImage>& t) {
  if (!t || t->empty()) return false;
  std::size_t n = t->texel_count();
  switch (t->format) {
    case TexelFormat::kSrgb8:
    case TexelFormat::kRgbe:
      return t->packed.size() == n;
    case TexelFormat::kHalf:
      return t->half.size() == 3 * n;
    case TexelFormat::kFloat:
      return t->rgb.size() == 3 * n;
  }
  return false;
}

uint32_t cell_of(double x, uint32_t n) {
  uint32_t c = std::min(n - 1, uint32_t(x * n));
  if (c > 0 && x < double(c) / n) return c - 1;
  if (c + 1 < n && x >= double(c + 1) / n) return c + 1;
  return c;
}

}  // namespace

// --- PiecewiseConstant1D ---

// The running sums of the weights, rounded to units (so that a sum that the weights give exactly,
// such as 1/4 of the total, is a step of exactly its share), then made to give every cell of
// weight > 0 at least one unit and to end at exactly kUnits: a forward pass lifts each such
// cell's end one unit above its start where rounding left it none, and a backward pass from
// kUnits lowers the ends that the lifts pushed too far. There are at most kMaxCells cells, so
// the forward pass stays below 2^32 and the backward one above 0.
PiecewiseConstant1D::PiecewiseConstant1D(std::vector<double> f) {
  if (f.empty()) f.push_back(0);
  const std::size_t n = f.size();
  double sum = 0, largest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    f[i] = i < kMaxCells && std::isfinite(f[i]) ? std::abs(f[i]) : 0.0;
    sum += f[i], largest = std::max(largest, f[i]);
  }
  integral_ = sum / double(n);
  cdf_.assign(n + 1, 0);
  if (!(largest > 0)) return;  // all zero: the CDF stays 0 and nothing is sampled
  // The sums of the weights over the largest, which cannot overflow.
  double total = 0;
  for (double w : f)
    total += w / largest;
  double running = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(f[i] > 0)) {
      cdf_[i + 1] = cdf_[i];
      continue;
    }
    running += f[i] / largest;
    const double rounded = std::nearbyint(std::min(1.0, running / total) * kUnits);
    cdf_[i + 1] = std::max(uint32_t(rounded), cdf_[i] + 1);
  }
  cdf_[n] = kUnits;
  for (std::size_t i = n - 1; i > 0; --i)
    cdf_[i] = std::min(cdf_[i], cdf_[i + 1] - (f[i] > 0 ? 1 : 0));
  build_guide();
}

// g spans of kUnits / g units, one per kCellsPerGuide cells: entry k is the cell of span k's
// first unit, ⌈k·kUnits / g⌉, and the last entry the last cell.
void PiecewiseConstant1D::build_guide() {
  const uint32_t n = size();
  const uint32_t g = (n + kCellsPerGuide - 1) / kCellsPerGuide;
  guide_.resize(std::size_t(g) + 1);
  first_step_ = std::bit_floor(n);  // the guide's entries are searched over all cells
  for (uint32_t k = 0; k < g; ++k) {
    const uint64_t first = ((uint64_t(k) << 31) + g - 1) / g;
    guide_[k] = cell_within(uint32_t(first), 0, n - 1);
  }
  // The last entry is the last cell of weight > 0, the one that holds the last unit (not the
  // last cell: a table that ends in empty cells, such as the marginal of a map whose lower half
  // is black, would have a last span over all of them, and every search as many steps).
  guide_[g] = cell_within(kUnits - 1, 0, n - 1);
  uint32_t longest = 0;
  for (uint32_t k = 0; k < g; ++k)
    longest = std::max(longest, guide_[k + 1] - guide_[k]);
  first_step_ = longest > 0 ? std::bit_floor(longest) : 0;
}

// The last cell i in [lo, hi] with cdf[i] ≤ U (the caller knows cdf[lo] ≤ U < cdf[hi + 1]);
// cells of zero weight have empty steps and are passed over. A binary search whose steps are
// selects rather than branches, and always as many as the table's longest guided span needs
// (first_step_, then halves): a search's branches taken at random, and a loop whose trip count
// varied with the span, were mispredicted and threw away the loads the next rows had started.
// An index past hi is held at hi + 1, whose entry is above U.
uint32_t PiecewiseConstant1D::cell_within(uint32_t units, uint32_t lo, uint32_t hi) const {
  const uint32_t* cdf = cdf_.data();
  uint32_t i = lo;
  for (uint32_t step = first_step_; step > 0; step /= 2) {
    const uint32_t j = std::min(i + step, hi + 1);
    i = cdf[j] <= units ? j : i;
  }
  return i;
}

double PiecewiseConstant1D::sample_continuous(double u, double* pdf, uint32_t* cell) const {
  const uint32_t n = size();
  u = u >= 0 ? std::min(u, kOneMinusEpsilon) : 0.0;  // NaN too: to 0
  if (guide_.empty()) {                              // all weights zero
    if (pdf) *pdf = 0;
    if (cell) *cell = std::min(n - 1, uint32_t(u * n));
    return u;
  }
  const double scaled = u * kUnits;  // exact: kUnits is a power of two
  const uint32_t at = units(u), k = guide_index(at);
  const uint32_t i = cell_within(at, guide_[k], guide_[k + 1]);
  const uint32_t start = cdf_[i], step = cdf_[i + 1] - start;  // step ≥ 1: i holds `at`
  const double du = (scaled - double(start)) / double(step);
  if (pdf) *pdf = pdf_of_cell(i);
  if (cell) *cell = i;
  // i/n ≤ x < (i + 1)/n as cell_of sees the edges, though du or the division round up.
  double x = (double(i) + du) / n, end = double(i + 1) / n;
  return x < end ? x : std::nextafter(end, 0.0);
}

double PiecewiseConstant1D::pdf(double x) const {
  if (!(x >= 0 && x < 1)) return 0;
  return pdf_of_cell(cell_of(x, size()));
}

// --- PiecewiseConstant2D ---

PiecewiseConstant2D::PiecewiseConstant2D(const std::vector<double>& f, uint32_t nu, uint32_t nv)
    : PiecewiseConstant2D(nu, nv, [&](uint32_t v, std::vector<double>& row) {
        for (uint32_t u = 0; u < row.size(); ++u) {
          std::size_t k = std::size_t(v) * row.size() + u;
          row[u] = k < f.size() ? f[k] : 0.0;
        }
      }) {}

PiecewiseConstant2D::PiecewiseConstant2D(
    uint32_t nu, uint32_t nv, const std::function<void(uint32_t, std::vector<double>&)>& fill) {
  nu = std::max(nu, 1u), nv = std::max(nv, 1u);
  conditional_.reserve(nv);
  std::vector<double> row_weights(nv);
  for (uint32_t v = 0; v < nv; ++v) {
    std::vector<double> row(nu, 0.0);
    fill(v, row);
    conditional_.emplace_back(std::move(row));
    row_weights[v] = conditional_.back().integral();
  }
  marginal_ = PiecewiseConstant1D(std::move(row_weights));
}

PiecewiseConstant2D::Sample PiecewiseConstant2D::sample(double u1, double u2) const {
  Sample s;
  double pdf_v = 0, pdf_u = 0;
  s.v = marginal_.sample_continuous(u2, &pdf_v, &s.cell_v);
  s.u = conditional_[s.cell_v].sample_continuous(u1, &pdf_u, &s.cell_u);
  // The joint density, the row's times the column's: the two densities are the cells' own
  // (pdf_of_cell), so this is pdf_of_cells(cell_u, cell_v), bit for bit, as pdf() computes it,
  // without reading the tables again (0 where a table samples nothing).
  s.pdf = pdf_v * pdf_u;
  return s;
}

void PiecewiseConstant2D::sample_many(std::size_t n, const double* u1, const double* u2,
                                      Sample* out) const {
  // The marginal's density rides in out[i].pdf between the two passes.
  for (std::size_t i = 0; i < n; ++i)
    out[i].v = marginal_.sample_continuous(u2[i], &out[i].pdf, &out[i].cell_v);
  // Rows kAhead on have their guide entries fetched, rows kAhead / 2 on the cells those lead
  // to: each row's reads then find the caches warm (a row's chain of dependent misses, guide
  // → CDF, was most of the environment's sampling time).
  constexpr std::size_t kAhead = 8;
  auto row = [&](std::size_t i) -> const PiecewiseConstant1D& {
    return conditional_[out[i].cell_v];
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (i + kAhead < n) row(i + kAhead).prefetch_guide(u1[i + kAhead]);
    if (i + kAhead / 2 < n) row(i + kAhead / 2).prefetch_cells(u1[i + kAhead / 2]);
    Sample& s = out[i];
    double pdf_u = 0;
    s.u = conditional_[s.cell_v].sample_continuous(u1[i], &pdf_u, &s.cell_u);
    s.pdf *= pdf_u;  // as sample() computes it
  }
}

double PiecewiseConstant2D::pdf(double u, double v) const {
  if (!(u >= 0 && u < 1 && v >= 0 && v < 1) || conditional_.empty()) return 0;
  uint32_t nv = marginal_.size(), nu = conditional_[0].size();
  return pdf_of_cells(cell_of(u, nu), cell_of(v, nv));
}

void PiecewiseConstant2D::prefetch_pdf(double u, double v) const {
  if (!(u >= 0 && u < 1 && v >= 0 && v < 1)) return;
  const uint32_t nv = marginal_.size(), nu = conditional_[0].size();
  conditional_[cell_of(v, nv)].prefetch_cell(cell_of(u, nu));
}

double PiecewiseConstant2D::pdf_of_cells(uint32_t iu, uint32_t iv) const {
  // The row's density times the column's within it: what sample() draws the cell with.
  return marginal_.pdf_of_cell(iv) * conditional_[iv].pdf_of_cell(iu);
}

std::size_t PiecewiseConstant2D::bytes() const {
  std::size_t b = marginal_.bytes() + conditional_.capacity() * sizeof(PiecewiseConstant1D);
  for (const auto& c : conditional_)
    b += c.bytes();
  return b;
}

// --- EnvironmentMap ---

EnvironmentMap::EnvironmentMap(Image image, double scale, const glm::dmat3& rotation)
    : EnvironmentMap(std::make_shared<const TexelImage>(float_texels(sanitized(std::move(image)))),
                     scale, rotation) {}

EnvironmentMap::EnvironmentMap(std::shared_ptr<const TexelImage> texels, double scale,
                               const glm::dmat3& rotation)
    : texels_(usable(texels) ? std::move(texels)
                             : std::make_shared<const TexelImage>(float_texels(Image(1, 1)))),
      scale_(scale > 0 && std::isfinite(scale) ? scale : 0.0),
      rotation_(rotation) {
  build_distribution();
}

glm::dvec3 EnvironmentMap::texel(uint32_t x, uint32_t y) const {
  return glm::dvec3(texels_->at(x, y));
}

glm::dvec3 EnvironmentMap::to_image(const glm::dvec3& d) const {
  return glm::transpose(rotation_) * d;
}

EnvironmentMap::ImagePoint EnvironmentMap::to_image_point(const glm::dvec3& d) {
  if (!is_finite(d)) return {0, 0, 0};
  // |(x, y)| and |d| by square roots where no square can overflow or leave double's normal
  // range (the render's directions are unit: within 1 ulp of std::hypot's, which cost as much
  // as the two arc tangents on the sky scene, by perf), by std::hypot otherwise.
  const double largest = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
  const bool plain = largest > 1e-100 && largest < 1e100;
  const double xy = d.x * d.x + d.y * d.y;
  double rxy = plain ? std::sqrt(xy) : std::hypot(d.x, d.y);
  double len = plain ? std::sqrt(xy + d.z * d.z) : std::hypot(rxy, d.z);
  if (!(len > 0)) return {0, 0, 0};
  double phi = std::atan2(d.y, d.x);  // (−π, π]; 0 for a direction along ±z
  if (phi < 0) phi += 2 * kPi;
  double u = phi / (2 * kPi);
  if (u >= 1) u -= 1;  // φ just below 0 rounds to 2π: the same place as u = 0
  double v = std::min(std::atan2(rxy, d.z) / kPi, kOneMinusEpsilon);
  return {u, v, rxy / len};
}

glm::dvec3 EnvironmentMap::radiance_uv(double u, double v) const {
  LinearRgb<double> c = environment_texel_lookup<double>(*texels_, u, v);
  return glm::dvec3(c.r, c.g, c.b) * scale_;
}

glm::dvec3 EnvironmentMap::radiance(const glm::dvec3& dir_world) const {
  ImagePoint p = to_image_point(to_image(dir_world));
  return radiance_uv(p.u, p.v);
}

EnvironmentSample EnvironmentMap::sample(double u1, double u2) const {
  EnvironmentSample s;
  direction_of(distribution_.sample(u1, u2), s);
  return s;
}

void EnvironmentMap::sample_many(EnvironmentBatch& b) const {
  const std::size_t n = b.u1.size();
  distribution_.sample_many(n, b.u1.data(), b.u2.data(), b.uv.data());
  constexpr std::size_t kAhead = 4;  // rows whose texels are fetched ahead of their lookup
  for (std::size_t i = 0; i < n; ++i) {
    if (i + kAhead < n) prefetch_texels(b.uv[i + kAhead].u, b.uv[i + kAhead].v);
    direction_of(b.uv[i], b.out[i]);
  }
}

// The texels the lookup at (u, v) reads, found as it finds them: its left column's, in its two
// rows (the one above or the one below the point's, as v falls). The right column's usually
// lie in the same lines.
void EnvironmentMap::prefetch_texels(double u, double v) const {
  const TexelImage& t = *texels_;
  const TexelSpan<double> sx = repeat_span(u * t.width, t.width);
  const TexelSpan<double> sy = clamp_span(v * t.height, t.height);
  for (const uint32_t row : {sy.a, sy.b}) {
    const std::size_t at = std::size_t(row) * t.width + sx.a;
    switch (t.format) {
      case TexelFormat::kSrgb8:
      case TexelFormat::kRgbe:
        __builtin_prefetch(t.packed.data() + at);
        break;
      case TexelFormat::kHalf:
        __builtin_prefetch(t.half.data() + 3 * at);
        break;
      case TexelFormat::kFloat:
        __builtin_prefetch(t.rgb.data() + 3 * at);
        break;
    }
  }
}

// Each field written once, in place: a sample built in a local and copied out was stored in
// parts and reloaded whole, a store-forwarding stall per row (perf: a third of sample_many's
// own samples).
void EnvironmentMap::direction_of(const PiecewiseConstant2D::Sample& uv,
                                  EnvironmentSample& s) const {
  const auto invalid = [&] {
    s.wi = rotation_ * glm::dvec3(0, 0, 1);
    s.le = glm::dvec3(0, 0, 0);
    s.pdf = 0;
  };
  if (!(uv.pdf > 0)) return invalid();
  // φ = 2π·u and θ = π·v = 2π·(v/2) (v/2 is exact), by the warps' sincos of a turn: within
  // 3e-16 of the true values, and a fifth of libm's sincos's cost, which was a quarter of an
  // environment sample's.
  const SinCos phi = sincos_2pi(uv.u), theta = sincos_2pi(0.5 * uv.v);
  const double sin_theta = theta.sin;
  if (!(sin_theta > 0)) return invalid();  // exactly on the top pole: no density in solid angle
  const glm::dvec3 d(sin_theta * phi.cos, sin_theta * phi.sin, theta.cos);
  s.wi = rotation_ * d;
  s.le = radiance_uv(uv.u, uv.v);
  s.pdf = uv.pdf / (2 * kPi * kPi * sin_theta);
}

double EnvironmentMap::pdf(const glm::dvec3& dir_world) const {
  if (!can_sample()) return 0;
  return pdf_at(to_image_point(to_image(dir_world)));
}

double EnvironmentMap::pdf_at(const ImagePoint& p) const {
  if (!(p.sin_theta > 0)) return 0;
  return distribution_.pdf(p.u, p.v) / (2 * kPi * kPi * p.sin_theta);
}

EnvironmentMap::Seen EnvironmentMap::seen(const glm::dvec3& dir_world) const {
  ImagePoint p = to_image_point(to_image(dir_world));
  return {radiance_uv(p.u, p.v), can_sample() ? pdf_at(p) : 0.0};
}

void EnvironmentMap::seen_many(EnvironmentSeenBatch& b) const {
  const std::size_t n = b.dir.size();
  b.point.resize(n), b.seen.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    b.point[i] = to_image_point(to_image(b.dir[i]));
  const bool sampled = can_sample();
  constexpr std::size_t kAhead = 4;  // rows whose texels and CDF entries are fetched ahead
  for (std::size_t i = 0; i < n; ++i) {
    if (i + kAhead < n) {
      const ImagePoint& ahead = b.point[i + kAhead];
      prefetch_texels(ahead.u, ahead.v);
      if (sampled) distribution_.prefetch_pdf(ahead.u, ahead.v);
    }
    const ImagePoint& p = b.point[i];
    b.seen[i] = {radiance_uv(p.u, p.v), sampled ? pdf_at(p) : 0.0};
  }
}

// Φ = π r² ∫ s·lum(E(ω)) dω: the light arriving from each direction ω is a parallel beam, and
// the part of it that can reach the scene crosses the disc of radius r facing ω (area π r²)
// around the scene's bounding sphere (pbrt-v4's ImageInfiniteLight::Phi, which sums the same
// over its equal-area texels).
double EnvironmentMap::power_estimate(double scene_radius) const {
  double r = std::isfinite(scene_radius) ? scene_radius : 0.0;
  return kPi * r * r * luminance_integral_;
}

std::size_t EnvironmentMap::bytes() const {
  return sizeof(*this) + texels_->bytes() + distribution_.bytes();
}

// The sampling weights. The lookup is bilinear, so a texel lights the cells around its own
// (up to half a cell into each neighbour): a weight built from each texel alone (pbrt-v4's
// choice, which suits its nearest-texel lookup) would be 0 in a black cell next to a bright
// one where radiance() is not, and MIS would then miss that light. Each cell's weight is
// instead the exact average over the cell of the bilinear luminance — separable weights
// (1/8, 3/4, 1/8) over the 3×3 texels around it, wrapping in u and clamping in v as the
// lookup does — which is > 0 wherever radiance() is > 0 in the cell (every weight is > 0 and
// Rec. 709's are too). Times sin θ of the row's centre, the Jacobian of (u, v) ↦ ω up to the
// constant 2π² (pbrt-v4 likewise takes the Jacobian at the cell centre).
void EnvironmentMap::build_distribution() {
  const uint32_t w = texels_->width, h = texels_->height;
  // Row by row: each row's luminance is decoded once, into its mean and its horizontally
  // filtered row, of which three are held at a time (rows y − 1, y, y + 1, clamped); the
  // tables are the only arrays of the image's size besides the texels.
  std::vector<double> row_mean(h, 0.0), lum(w);
  auto across_row = [&](uint32_t y, std::vector<double>& out) {
    for (uint32_t x = 0; x < w; ++x)
      lum[x] = rec709_luminance(texel(x, y));
    for (uint32_t x = 0; x < w; ++x)
      row_mean[y] += lum[x];
    row_mean[y] /= w;
    for (uint32_t x = 0; x < w; ++x)
      out[x] =
          kSide * lum[wrap(int64_t(x) - 1, w)] + kCentre * lum[x] + kSide * lum[wrap(x + 1, w)];
  };
  std::vector<double> up(w), mid(w), down(w);
  across_row(0, mid);
  up = mid;  // row −1 clamps to row 0
  distribution_ = PiecewiseConstant2D(w, h, [&](uint32_t y, std::vector<double>& weight) {
    if (y + 1 < h) {
      across_row(y + 1, down);
    } else {
      down = mid;  // row h clamps to row h − 1
    }
    // The scale only multiplies the density's weights (it cancels), so it enters as "black
    // or not": multiplying by it could overflow for a huge s.
    double sin_theta = scale_ > 0 ? std::sin(kPi * (y + 0.5) / h) : 0.0;
    for (uint32_t x = 0; x < w; ++x)
      weight[x] = (kSide * up[x] + kCentre * mid[x] + kSide * down[x]) * sin_theta;
    std::swap(up, mid);
    std::swap(mid, down);
  });
  luminance_integral_ = scale_ * luminance_sphere_integral(row_mean);
}

// ∫ lum(E(ω)) dω over the sphere for the bilinear map, exactly: over a whole turn in u the
// interpolation between texel centres integrates to the row's mean, so ∫ E du is the linear
// interpolation of the row means in v (constant above the first and below the last centre,
// as the lookup clamps), integrated against dω = 2π² sin(πv) du dv in closed form.
double EnvironmentMap::luminance_sphere_integral(const std::vector<double>& mean) const {
  const uint32_t h = texels_->height;
  auto centre = [&](uint32_t y) { return (y + 0.5) / h; };
  double total = band_integral(0, centre(0), mean[0], mean[0]);
  for (uint32_t y = 0; y + 1 < h; ++y)
    total += band_integral(centre(y), centre(y + 1), mean[y], mean[y + 1]);
  total += band_integral(centre(h - 1), 1, mean[h - 1], mean[h - 1]);
  return std::max(0.0, total);
}

}  // namespace raylane
