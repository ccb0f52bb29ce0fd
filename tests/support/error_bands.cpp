// Error bands of the float packet kernels against the double references (docs/hard-cases.md §0).
//
// Method. For each kernel we follow its float operations one by one and keep, in double, an
// interval that holds the value the kernel computes (pbrt-v4 does this with its `Interval`
// class for quadrics, src/pbrt/shapes.h; our intervals run beside the kernel instead of in
// it). One float rounding of an exact value x gives x(1 + δ), |δ| ≤ u = 2^-24; a chain of n
// roundings on a product or on a sum of terms of one sign gives a relative error ≤ γn =
// nu/(1 − nu) (Higham, "Accuracy and Stability of Numerical Algorithms", §3.1; pbrt-v4
// `gamma`). Where plain intervals would lose the structure that keeps the error small (the
// Hearn–Baker distance of a line from a point, and the edge functions of the watertight
// triangle test) the bound is derived by hand, below, from the kernel's operations.
//
// The reference runs the same formulas in double on the same float inputs, so its own error
// obeys the same bounds with u_d = 2^-53 = 2^-29·u: every bound is widened by 1 + 2^-28 to
// cover it, so that |margin| > bound settles the reference's answer as well as the kernel's.
#include "support/error_bands.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "raylane/core/float_util.h"
#include "raylane/trace/brute_force.h"
#include "support/interval.h"

namespace raylane::testing {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double u = kFloatUnitRoundoff;
constexpr double kRefSlack = 1 + 0x1p-28;  // the reference's own error (see above)

double gamma(int n) {
  return gamma_float(n);
}
double sq(double x) {
  return x * x;
}

// The criterion for a decision the kernel takes on the sign of a value it holds in `kernel`
// while the reference holds `ref`.
Criterion criterion(double ref, Interval kernel) {
  return {ref, std::max(gap(ref, kernel.lo), gap(ref, kernel.hi)) * kRefSlack};
}
// A hit needs every criterion: one clear miss decides a miss, all clear hits a hit.
RayClass both(RayClass a, RayClass b) {
  if (a == RayClass::kClearMiss || b == RayClass::kClearMiss) return RayClass::kClearMiss;
  if (a == RayClass::kClearHit && b == RayClass::kClearHit) return RayClass::kClearHit;
  return RayClass::kBand;
}

// A hit that needs several criteria at once: one clear miss settles a miss, all clear hits a
// hit. `decisive` is the clearest miss, else the band criterion nearest its edge, else the
// weakest hit.
struct AllOf {
  RayClass cls = RayClass::kClearHit;
  Criterion decisive{kInf, 0};
  void add(const Criterion& c) {
    RayClass v = c.verdict();
    if (v == RayClass::kClearMiss) {
      if (cls != RayClass::kClearMiss || c.ratio() > decisive.ratio()) decisive = c;
      cls = RayClass::kClearMiss;
    } else if (cls != RayClass::kClearMiss && v == RayClass::kBand) {
      if (cls == RayClass::kClearHit || c.ratio() < decisive.ratio()) decisive = c;
      cls = RayClass::kBand;
    } else if (cls == RayClass::kClearHit && c.ratio() < decisive.ratio()) {
      decisive = c;
    }
  }
};

// ---- What the kernels share ----

// Which t the kernel commits (commit_solid_hit in simd/packet.h): the near end tn if it lies
// in (tmin, tmax), else the far end tf if that does; tf ≥ tn. `line` is the verdict on
// whether the ray's line meets the solid; a triangle passes tn = tf = its t.
PrimVerdict commit_range(RayClass line, Interval tn, Interval tf, const Rayd& ray,
                         const Criterion& decisive, double t_ref) {
  PrimVerdict v{RayClass::kClearMiss, hull(tn, tf), t_ref, decisive};
  if (line == RayClass::kClearMiss) return v;
  auto inside = [&](Interval t) { return t.lo > ray.tmin && t.hi < ray.tmax; };
  auto below = [&](Interval t) { return t.hi <= ray.tmin; };
  auto above = [&](Interval t) { return t.lo >= ray.tmax; };
  RayClass range = RayClass::kBand;
  if (inside(tn)) {
    range = RayClass::kClearHit, v.t = tn;
  } else if (above(tn)) {
    range = RayClass::kClearMiss;
  } else if (below(tn)) {
    if (inside(tf)) range = RayClass::kClearHit, v.t = tf;
    if (below(tf) || above(tf)) range = RayClass::kClearMiss;
  }
  v.cls = both(line, range);
  return v;
}

// Errors of the inputs p̂ = p + δp, q̂ = q + δq of kernel_line_distance, split into the part
// inside the plane of p and q's motion (`in_plane`: first order in the distance) and the part
// across it (`across`: second order, it adds in quadrature). For spheres all of it counts as
// in-plane; for cylinders "across" is the axial direction, which the distance between the
// axis and the ray's line ignores.
struct InputErrors {
  double in_plane = 0, across = 0;
  double total() const { return in_plane + across; }
};

// The kernel's |l̂|, where l = p − (p·q / q·q)·q is the vector from the origin to the line
// {p + s·q} at its closest point (Hearn and Baker's discriminant; Haines et al. 2019, Ray
// Tracing Gems ch. 7), computed in float as  k = fl(fl(p̂·q̂) / fl(q̂·q̂)),
// l̂_i = fl(p̂_i − fl(k·q̂_i)).  L = |l|, P = |p|, Q = |q| are the reference's values.
//  1. The distance of the origin from the line (p̂, q̂) is within ep + K·eq of L in the plane
//     (ep, eq the in-plane errors; K = (P + Ep)/(Q − Eq) ≥ |s| at the nearest point of either
//     line: take the other line's nearest parameter), and the across errors add
//     (ep' + K·eq')² under the square root: the nearest point moves across by that much.
//  2. k̂ differs from k(p̂, q̂) by Δk with |Δk|·|q̂| ≤ γ10·|p̂| (γ3 on the dot products, one
//     rounding for the quotient). That error runs along q̂, orthogonal to l(p̂, q̂), so it adds
//     in quadrature too: second order (this is why the Hearn–Baker form is accurate, and why a
//     first-order bound γ10|p| on |l̂| would be needlessly wide).
//  3. The products k·q̂_i add at most u·|k||q̂| ≤ u|p̂|(1 + γ10) in norm; the subtractions
//     scale each component by (1 + δ_i), |δ_i| ≤ u.
Interval kernel_line_distance(double L, double P, double Q, InputErrors ep, InputErrors eq) {
  double Ep = ep.total(), Eq = eq.total();
  if (!(Q > Eq)) return {0.0, kInf};
  double K = (P + Ep) / (Q - Eq);
  double near = L - ep.in_plane - K * eq.in_plane, far = L + ep.in_plane + K * eq.in_plane;
  double across = ep.across + K * eq.across, along = gamma(10) * (P + Ep);
  double products = u * (P + Ep) * (1 + gamma(10));
  double lo = std::max(0.0, near - products) * (1 - u);
  double hi = (std::sqrt(far * far + across * across + along * along) + products) * (1 + u);
  return widen({lo, hi}, 0.0);
}

// The kernel's discriminant fl(fl(r·r) − fl(Σ l̂_i²)) (a sum of three squares: γ3).
Interval kernel_discriminant(double r, Interval l_hat) {
  Interval rr = rounded(Interval::point(r * r));
  return rounded(rr - widen(square_nonneg(l_hat), gamma(3)));
}

// The roots as the kernels take them (Press form, solid.h): sq = fl(√fl(a·disc)),
// q = −fl(b ∓ sq) with the sign of b, t0 = fl(c/q), t1 = fl(q/a); near = min, far = max.
// Near grazing, disc → 0 and √ stretches the interval of disc: the t error grows like
// E_disc/√disc on its own, which is the conditioning a fixed multiple of u·|t| misses.
struct Roots {
  Interval near, far;
};
Roots kernel_roots(Interval a, Interval b, Interval c, Interval disc) {
  Interval sqrt_disc = rounded(isqrt(rounded(a * clamp_nonneg(disc))));
  auto branch = [&](Interval bb, bool negative) {
    Interval q = negative ? -rounded(bb - sqrt_disc) : -rounded(bb + sqrt_disc);
    Interval t0 = rounded(c / q), t1 = rounded(q / a);
    return Roots{imin(t0, t1), imax(t0, t1)};
  };
  if (b.hi < 0) return branch(b, true);
  if (b.lo >= 0) return branch(b, false);
  Roots neg = branch({b.lo, 0.0}, true), pos = branch({0.0, b.hi}, false);
  return {hull(neg.near, pos.near), hull(neg.far, pos.far)};
}

// ---- Triangles: the watertight test (Woop, Benthin and Wald 2013, JCGT 2(1)) ----

// The kernel's axes (WoopSetup in triangle.h: ties go to the lowest axis; x, y swapped when
// d_kz < 0) and its sheared vertex coordinates, in double, with their error bounds.
struct ShearedVertex {
  double x, y, z, ex, ey, ez;
};
struct Shear {
  int kx, ky, kz;
  double sx, sy, sz;
};
Shear kernel_shear(const glm::dvec3& d) {
  glm::dvec3 a = abs(d);
  int kz = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
  int kx = (kz + 1) % 3, ky = (kz + 2) % 3;
  if (d[kz] < 0) std::swap(kx, ky);
  return {kx, ky, kz, d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]};
}
// Translation, then shear. In float: â_k = fl(p_k − o_k) (one rounding), ŝx = fl(d_kx·fl(1/d_kz))
// (two), x̂ = fl(â_kx − ŝx·â_kz): one rounding with FMA, two without, so
//   |x̂ − x| ≤ γ2|a_kx| + γ5|Sx·a_kz|,  and ẑ = fl(fl(1/d_kz)·â_kz): |ẑ − z| ≤ γ3|z|.
// (pbrt-v4 Triangle::Intersect bounds the same quantities, δx = γ5(max|x| + max|z|).)
ShearedVertex shear_vertex(const glm::vec3& p, const Rayd& ray, const Shear& s) {
  glm::dvec3 a = glm::dvec3(p) - ray.o;
  double zx = s.sx * a[s.kz], zy = s.sy * a[s.kz];
  ShearedVertex v;
  v.x = a[s.kx] - zx;
  v.y = a[s.ky] - zy;
  v.z = s.sz * a[s.kz];
  v.ex = (gamma(2) * std::abs(a[s.kx]) + gamma(5) * std::abs(zx)) * kRefSlack;
  v.ey = (gamma(2) * std::abs(a[s.ky]) + gamma(5) * std::abs(zy)) * kRefSlack;
  v.ez = gamma(3) * std::abs(v.z) * kRefSlack;
  return v;
}
// The edge function a·b − c·d from perturbed inputs (|δa| ≤ ea, ...): the first-order and
// product terms of the perturbation, plus the rounding of the difference of products:
// ≤ 2u|result| with FMA (Kahan's algorithm; Jeannerod, Louvet and Muller 2013) and
// ≤ γ2(|a·b| + |c·d|) as plain a·b − c·d on SSE4.2 (lanes.h); the latter bounds both.
double edge_error(double a, double ea, double b, double eb, double c, double ec, double d,
                  double ed) {
  double inputs =
      std::abs(a) * eb + std::abs(b) * ea + ea * eb + std::abs(c) * ed + std::abs(d) * ec + ec * ed;
  double rounding = gamma(2) * ((std::abs(a) + ea) * (std::abs(b) + eb) +
                                (std::abs(c) + ec) * (std::abs(d) + ed));
  return (inputs + rounding) * kRefSlack;
}

// The sign test on U, V, W: all of one sign is a hit, two opposite signs a miss. The
// decisive criterion: for a hit, the edge function nearest its band (margin s·X); for a
// miss, the weaker of the two that prove it (margin −|X|).
Criterion edge_criterion(const double x[3], const double e[3]) {
  double ratio[3];
  for (int k = 0; k < 3; ++k)
    ratio[k] = e[k] > 0 ? x[k] / e[k] : (x[k] > 0 ? kInf : (x[k] < 0 ? -kInf : 0.0));
  int lo = int(std::min_element(ratio, ratio + 3) - ratio);
  int hi = int(std::max_element(ratio, ratio + 3) - ratio);
  if (ratio[lo] >= 0) return {x[lo], e[lo]};      // all ≥ 0: the smallest decides
  if (ratio[hi] <= 0) return {-x[hi], e[hi]};     // all ≤ 0: the largest decides
  int weaker = ratio[hi] < -ratio[lo] ? hi : lo;  // mixed: both opposite signs must hold
  return {-std::abs(x[weaker]), e[weaker]};
}

}  // namespace

const char* ray_class_name(RayClass c) {
  switch (c) {
    case RayClass::kClearHit:
      return "clear hit";
    case RayClass::kClearMiss:
      return "clear miss";
    case RayClass::kBand:
      return "band";
  }
  return "?";
}

RayClass Criterion::verdict() const {
  if (margin > bound) return RayClass::kClearHit;
  if (margin < -bound) return RayClass::kClearMiss;
  return RayClass::kBand;
}

double Criterion::ratio() const {
  if (bound > 0) return std::abs(margin) / bound;
  return margin == 0 ? 0.0 : kInf;
}

// Sphere kernel (sphere.h): f̂ = fl(o − ĉ), where the kernel's centre ĉ is within Ec of the
// reference's c (0 for a static sphere) — the only input error, the direction is exact: |f̂ − f|
// ≤ Ef = u|f| + (1 + u)·Ec. Then the Hearn–Baker distance (kernel_line_distance with p = f,
// q = d, Ep = Ef, Eq = 0), disc = fl(r²) − fl(|l̂|²); roots from a = fl(d·d) (γ3),
// b = fl(f̂·d) (|b̂ − f·d| ≤ Ef|d| + γ3|f̂||d|), c = fl(fl(|f̂|²) − fl(r²)).
// The decision is disc ≥ 0; its margin is the reference's r² − |l|² (docs/hard-cases.md S1).
namespace {
PrimVerdict classify_sphere(const glm::dvec3& centre, double Ec, double r, const Rayd& ray,
                            double t_ref) {
  glm::dvec3 f = ray.o - centre;
  const glm::dvec3& d = ray.d;
  double F = length(f), D = length(d), b = dot(f, d), dd = dot(d, d);
  double Ef = u * F + (1 + u) * Ec;
  double L = length(f - (b / dd) * d);
  Interval disc = kernel_discriminant(r, kernel_line_distance(L, F, D, {Ef, 0}, {}));
  Criterion side = criterion(r * r - L * L, disc);
  Interval a = widen(Interval::point(dd), gamma(3));
  Interval b_hat = Interval::around(b, (Ef * D + gamma(3) * (F + Ef) * D) * kRefSlack);
  Interval ff = {sq(std::max(0.0, F - Ef)) * (1 - gamma(3)), sq(F + Ef) * (1 + gamma(3))};
  Interval c = rounded(ff - rounded(Interval::point(r * r)));
  Roots t = kernel_roots(a, b_hat, c, disc);
  return commit_range(side.verdict(), t.near, t.far, ray, side, t_ref);
}
}  // namespace

PrimVerdict classify(const SphereTable& s, uint32_t row, const Rayd& ray) {
  return classify_sphere(glm::dvec3(s.center(row)), 0.0, s.r[row], ray, intersect_ref(s, row, ray));
}

// Moving sphere kernel (moving_sphere_packet.h): the centre at the ray's time t is
// ĉ_i = fl(c0_i + fl(t·m_i)), within u|t·m_i| + u|c_i| + u²|t·m_i| of c0_i + t·m_i per
// component; the reference's c (double, moving_sphere.h) is within 2^-53|c| of that, as t·m
// is exact in double. Then the sphere's kernel.
PrimVerdict classify(const MovingSphereTable& s, uint32_t row, const Rayd& ray) {
  glm::dvec3 c = s.center_at(row, ray.time);
  double tm = length(glm::dvec3(s.motion(row)) * ray.time), cc = length(c);
  double Ec = (u * cc + u * (1 + u) * tm + 0x1p-52 * cc) * kRefSlack;
  return classify_sphere(c, Ec, s.r[row], ray, intersect_ref(s, row, ray));
}

PrimVerdict classify(const CsgTable& c, uint32_t row, const Rayd& ray) {
  PrimVerdict out;
  out.t_ref = intersect_ref(c, row, ray);
  for (uint32_t i = c.leaf_begin[row]; i < c.leaf_begin[row] + c.leaf_count[row]; ++i) {
    uint32_t r = c.leaf_row[i];
    PrimVerdict v = c.leaf_kind[i] == kCsgSphere ? classify(c.spheres, r, ray)
                    : c.leaf_kind[i] == kCsgBox  ? classify(c.boxes, r, ray)
                                                 : classify(c.cylinders, r, ray);
    if (v.cls != RayClass::kClearMiss) {
      out.cls = RayClass::kBand;
      out.t = Interval::everything();
      out.decisive = {0, 1};
      return out;
    }
  }
  return out;
}

PrimVerdict classify(const SdfTable& s, uint32_t row, const Rayd& ray) {
  PrimVerdict out;
  out.t_ref = intersect_ref(s, row, ray);
  if (out.t_ref < std::numeric_limits<double>::infinity()) {
    out.cls = RayClass::kBand;
    out.t = Interval::everything();
    out.decisive = {0, 1};
  }
  return out;
}

// Box kernel (box.h): per axis t = fl(fl(bound − o)·fl(1/d)), three roundings: γ3|t| (pbrt-v4
// Bounds3::IntersectP; Ize 2013, "Robust BVH Ray Traversal"). A zero component gives ±inf or
// NaN exactly as in the reference (0·inf only when o lies in the plane; both skip it). Entry
// t0 = max of the near values, exit t1 = min of the far ones; hit when t0 ≤ t1, that is when
// near_i ≤ far_j for every pair of axes i ≠ j (i = j always holds: rounding is monotone and
// lo < hi). So the margins are the reference's far_j − near_i (the slab overlap, docs/hard-cases.md
// B2, B7), each against the sum of its two values' errors; comparing max and min as
// independent intervals would also count an axis against itself. The t of a clear hit is one
// of the slab values, so its error stays γ3|t| — no conditioning issue near an edge.
PrimVerdict classify(const BoxTable& bt, uint32_t row, const Rayd& ray) {
  glm::dvec3 lo(bt.lo(row)), hi(bt.hi(row));
  double tn[3], tf[3];
  Interval near[3], far[3];
  Interval t0 = Interval::point(-kInf), t1 = Interval::point(kInf);
  for (int k = 0; k < 3; ++k) {
    detail::box_slab(lo[k], hi[k], ray.o[k], ray.d[k], tn[k], tf[k]);
    near[k] = Interval::point(tn[k]), far[k] = Interval::point(tf[k]);
    if (ray.d[k] != 0) {
      Interval inv = rounded(Interval::point(1.0 / ray.d[k]));
      Interval a = rounded(rounded(Interval::point(lo[k] - ray.o[k])) * inv);
      Interval c = rounded(rounded(Interval::point(hi[k] - ray.o[k])) * inv);
      bool neg = std::signbit(ray.d[k]);
      near[k] = neg ? c : a;
      far[k] = neg ? a : c;
    }
    if (!std::isnan(tn[k])) t0 = imax(t0, near[k]);
    if (!std::isnan(tf[k])) t1 = imin(t1, far[k]);
  }
  AllOf overlap;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (i != j && !std::isnan(tn[i]) && !std::isnan(tf[j]))
        overlap.add(criterion(tf[j] - tn[i], far[j] - near[i]));
  return commit_range(overlap.cls, t0, t1, ray, overlap.decisive, intersect_ref(bt, row, ray));
}

// Cylinder kernel (cylinder.h). Besides its roundings the kernel differs from the reference in
// its inputs: it reads the stored float unit axis û = u + Δ where the reference normalises the
// axis in double (Δ computed here, split into Δ⊥ across the axis and Δ∥ along it), and the
// float height. The kernel's f⊥ = fl(f̂ − fl(fl(f̂·û)·û)) expands, with fa' = f̂·u, to
//   p + P⊥(δf) − (f̂·Δ)u − fa'·Δ − (f̂·Δ)Δ − e1·û − ρ1 + ρ2,
// where f̂ = fl(o − b) (|δf| ≤ u|f|; P⊥ removes its axial part), e1 ≤ γ3|f̂||û| (the dot
// product), ρ1 ≤ u|fâ||û| (the products), ρ2 ≤ u|pre| (the subtractions). The terms along u
// change the distance between the lines only in second order (InputErrors::across); the others
// are first order. Likewise for d⊥ (d is exact). These feed kernel_line_distance (the side
// test, C5: the margin is r² − dist(ray line, axis line)²) and the interval roots of the side;
// the axial slab is t = fl(fl(h − fa)·fl(1/da)) with fa, da within their bounds. Hit: side ok
// and max(side near, slab near) ≤ min(side far, slab far) — the second criterion (caps, rims).
InputErrors projected_errors(double F, double fa, double df, double P, glm::dvec3 delta,
                             glm::dvec3 u_d) {
  double d_par = std::abs(dot(delta, u_d)), d_perp = length(delta - dot(delta, u_d) * u_d);
  double dU = length(delta), s = 1 + dU, F1 = F * (1 + u), fa1 = std::abs(fa) + df;
  double e1 = gamma(3) * F1 * s;
  double rho1 = u * (fa1 + F1 * dU + e1) * s;
  InputErrors e;
  e.in_plane = df + fa1 * d_perp + F1 * dU * d_perp + e1 * d_perp + rho1;
  e.across = F1 * dU + fa1 * d_par + F1 * dU * d_par + e1 * (1 + d_par) + rho1;
  double rho2 = u * (P + e.total());
  e.in_plane = (e.in_plane + rho2) * kRefSlack;
  e.across = (e.across + rho2) * kRefSlack;
  return e;
}

// |x̂|² for x̂ = x + δ⊥ + δ∥ with x ⊥ δ∥ (δ∥ along the axis, x across it).
Interval norm2_interval(double X, InputErrors e) {
  return {sq(std::max(0.0, X - e.in_plane)), sq(X + e.in_plane) + sq(e.across)};
}

PrimVerdict classify(const CylinderTable& cyl, uint32_t row, const Rayd& ray) {
  glm::dvec3 axis(cyl.axis(row)), uf(cyl.unit_axis(row));
  double h = length(axis), hf = cyl.h[row], r = cyl.r[row];
  glm::dvec3 ud = axis / h;
  double dU = length(uf - ud), s = 1 + dU;
  glm::dvec3 f = ray.o - glm::dvec3(cyl.base(row));
  const glm::dvec3& d = ray.d;
  double fa = dot(f, ud), da = dot(d, ud);
  glm::dvec3 p = f - fa * ud, q = d - da * ud;
  double F = length(f), D = length(d), P = length(p), Q = length(q), b = dot(p, q), a = dot(q, q);
  double L = a > 0 ? length(p - (b / a) * q) : P;

  // f⊥ (f̂ rounded: δf ≤ u|f|) and d⊥ (d exact).
  InputErrors ep = projected_errors(F, fa, u * F, P, uf - ud, ud);
  InputErrors eq = projected_errors(D, da, 0.0, Q, uf - ud, ud);
  double Ep = ep.total(), Eq = eq.total();
  double e1f = gamma(3) * F * (1 + u) * s, e1d = gamma(3) * D * s;
  Interval disc = kernel_discriminant(r, kernel_line_distance(L, P, Q, ep, eq));
  Criterion side = criterion(r * r - L * L, disc);

  // |q̂|², |p̂|², p̂·q̂ (γ3 each): p and q lie across the axis, so the axial errors enter the
  // squares and the product only through their own squares and product.
  Interval a_hat = widen(norm2_interval(Q, eq), gamma(3));
  Interval pp_hat = widen(norm2_interval(P, ep), gamma(3));
  Interval b_hat =
      Interval::around(b, ep.in_plane * Q + P * eq.in_plane + ep.in_plane * eq.in_plane +
                              ep.across * eq.across + gamma(3) * (P + Ep) * (Q + Eq));
  Interval c_hat = rounded(pp_hat - rounded(Interval::point(r * r)));
  Roots side_t{Interval::everything(), Interval::everything()};
  if (a_hat.lo > 0) side_t = kernel_roots(a_hat, b_hat, c_hat, disc);

  Interval fa_hat = Interval::around(fa, (u * F * s + F * dU + e1f) * kRefSlack);
  Interval da_hat = Interval::around(da, (D * dU + e1d) * kRefSlack);
  Interval inv = rounded(Interval::point(1.0) / da_hat);
  Interval ta = rounded(-fa_hat * inv), tb = rounded(rounded(Interval::point(hf) - fa_hat) * inv);
  Interval z_near = Interval::everything(), z_far = Interval::everything();
  if (da_hat.lo > 0) z_near = ta, z_far = tb;
  if (da_hat.hi < 0) z_near = tb, z_far = ta;
  Interval t0 = imax(side_t.near, z_near), t1 = imin(side_t.far, z_far);

  // The reference's side roots (of a grazing line too: disc < 0 would miss anyway) and slab,
  // with the double height. The kernel's side near ≤ side far and slab near ≤ slab far always
  // (min/max of the same pair; monotone rounding), so max(near) ≤ min(far) needs only the two
  // cross comparisons: the line enters the side before leaving the slab and vice versa.
  double s0 = -kInf, s1 = kInf, z0 = -kInf, z1 = kInf;
  if (a > 0) solve_quadratic(a, b, P * P - r * r, a * std::max(0.0, r * r - L * L), s0, s1);
  if (da != 0) z0 = std::min(-fa / da, (h - fa) / da), z1 = std::max(-fa / da, (h - fa) / da);
  AllOf line;
  line.add(side);
  line.add(criterion(z1 - s0, z_far - side_t.near));
  line.add(criterion(s1 - z0, side_t.far - z_near));
  return commit_range(line.cls, t0, t1, ray, line.decisive, intersect_ref(cyl, row, ray));
}

// The kernel's t = fl(fl(fl(fl(U·za) + fl(V·zb)) + fl(W·zc)) / fl(fl(U + V) + W)), as a bound
// on |t_kernel − t| around the reference's t = Σ X·z_X / Σ X (X = U, V, W). Perturbation of the
// barycentric form: with X̂ = X + δX and ẑ = z + δz, Σ X̂ẑ − t·Σ X̂ = Σ δX(ẑ_X − t) + Σ X·δz_X
// exactly (since Σ X·z_X = t·Σ X), so before rounding t moves by at most
//   A = Σ E_X(|z_X − t| + Ez_X) + Σ |X|·Ez_X   over   |Σ X̂| ≥ |det| − Σ E_X.
// Each edge error is weighted by how far its vertex's depth is from t, not by the depth itself
// (an interval quotient T/det would lose that, ~10× wider for small far triangles). Then the
// roundings: the sum T gets γ3·Σ|X̂ẑ|, det gets γ2·Σ|X̂|, the quotient u. A small det (a ray
// near the triangle's plane: det ∝ |cos θ|) divides everything, which is the conditioning of
// docs/hard-cases.md §0 (grazing errors of 10^4 ulp and more); when det may vanish t is unbounded.
Interval kernel_triangle_t(const double x[3], const double e[3], const ShearedVertex* v[3]) {
  double det = x[0] + x[1] + x[2], T = x[0] * v[0]->z + x[1] * v[1]->z + x[2] * v[2]->z;
  double t = T / det, sum_e = 0, a = 0, sum_x = 0, sum_xz = 0;
  for (int k = 0; k < 3; ++k) {
    const ShearedVertex& w = *v[k];
    sum_e += e[k];
    a += e[k] * (std::abs(w.z - t) + w.ez) + std::abs(x[k]) * w.ez;
    sum_x += std::abs(x[k]) + e[k];
    sum_xz += (std::abs(x[k]) + e[k]) * (std::abs(w.z) + w.ez);
  }
  double det_lo = std::abs(det) - sum_e - gamma(2) * sum_x;
  if (!(det_lo > 0) || !std::isfinite(t)) return Interval::everything();
  double before_rounding = a / det_lo;
  double roundings =
      (gamma(3) * sum_xz + (std::abs(t) + before_rounding) * gamma(2) * sum_x) / det_lo;
  double err = before_rounding + roundings;
  err = (err + u * (std::abs(t) + err)) * kRefSlack;
  return Interval::around(t, err);
}

// Triangle kernel (triangle.h), the watertight test: sheared vertices (shear_vertex), edge
// functions U = cx·by − cy·bx, V, W (edge_error: input errors of translation and shear plus
// the difference of products); hit when all have one sign (and det ≠ 0, implied then). The
// margin is the reference's smallest edge function (docs/hard-cases.md T1–T3); t by
// kernel_triangle_t.
PrimVerdict classify(const TriangleTable& tri, uint32_t row, const Rayd& ray) {
  Shear s = kernel_shear(ray.d);
  ShearedVertex a = shear_vertex(tri.p0(row), ray, s), b = shear_vertex(tri.p1(row), ray, s),
                c = shear_vertex(tri.p2(row), ray, s);
  double x[3] = {difference_of_products(c.x, b.y, c.y, b.x),
                 difference_of_products(a.x, c.y, a.y, c.x),
                 difference_of_products(b.x, a.y, b.y, a.x)};
  double e[3] = {edge_error(c.x, c.ex, b.y, b.ey, c.y, c.ey, b.x, b.ex),
                 edge_error(a.x, a.ex, c.y, c.ey, a.y, a.ey, c.x, c.ex),
                 edge_error(b.x, b.ex, a.y, a.ey, b.y, b.ey, a.x, a.ex)};
  Criterion edges = edge_criterion(x, e);
  const ShearedVertex* vertices[3] = {&a, &b, &c};
  Interval t = kernel_triangle_t(x, e, vertices);
  return commit_range(edges.verdict(), t, t, ray, edges, intersect_ref(tri, row, ray));
}

}  // namespace raylane::testing
