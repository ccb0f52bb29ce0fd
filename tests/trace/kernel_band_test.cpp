// The packet kernels against the double references, with docs/hard-cases.md §0's classes: every
// ray is a clear hit, a clear miss or in the ambiguous band, from the error bounds of
// support/error_bands (no tolerance is guessed). Typed over the primitive kinds; seeded random
// rays and rays aimed at silhouettes, edges and rims so that the band is populated; world
// offsets 0 … 1e5 and object scales 1e-3 … 1e3; streams whose last packet is partly filled
// and invalid rays mixed in, so packets run with inactive lanes. Moving spheres: every ray has
// its own time (the shutter's ends, its middle, random), so the kernels take times per lane.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "raylane/bvh/bvh.h"
#include "raylane/core/float_util.h"
#include "raylane/trace/brute_force.h"
#include "raylane/trace/simd_tracer.h"
#include "support/error_bands.h"
#include "support/random_scene.h"

namespace raylane {
namespace {

using testing::classify_closest;
using testing::RayClass;
using testing::RayVerdict;
using testing::round_to_float;
using Rng = std::mt19937_64;

// ---- The tracing paths under test: one value per way from baseline code to the kernels ----

// Every ISA with both traversals: packets (rays in lanes) and single rays over the 8-wide
// tree (rows in lanes), which reach the same kernels through their other lane layout.
struct KernelPath {
  Isa isa;
  Traversal traversal;
  std::string name;
};

std::vector<KernelPath> kernel_paths() {
  std::vector<KernelPath> paths;
  for (Traversal traversal : {Traversal::kPackets, Traversal::kSingleRays})
    for (Isa isa : supported_isas())
      paths.push_back({isa, traversal,
                       std::string(isa_name(isa)) + "-" + std::string(traversal_name(traversal))});
  return paths;
}

void trace_closest(const KernelPath& path, const Scene& scene, const Bvh& bvh,
                   const RayStream& rays, HitStream& hits) {
  SimdTracer(path.isa, path.traversal).closest(scene, bvh, rays, hits);
}

void trace_occluded(const KernelPath& path, const Scene& scene, const Bvh& bvh,
                    const RayStream& rays, HitStream& hits) {
  SimdTracer(path.isa, path.traversal).occluded(scene, bvh, rays, hits);
}

// ---- Random geometry ----

double uniform(Rng& g, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(g);
}

glm::dvec3 unit_vector(Rng& g) {
  double z = uniform(g, -1, 1), phi = uniform(g, 0, 2 * M_PI), s = std::sqrt(1 - z * z);
  return {s * std::cos(phi), s * std::sin(phi), z};
}

// A unit vector orthogonal to the unit vector n.
glm::dvec3 orthogonal_unit(Rng& g, const glm::dvec3& n) {
  glm::dvec3 v{};
  do
    v = cross(n, unit_vector(g));
  while (length_squared(v) < 1e-6);
  return normalize(v);
}

// A relative offset that puts an aimed ray inside or just outside the band: 0, or ±2^-24·2^k
// for k in [0, 10). Rounding the direction to float adds another u-sized offset.
double band_jitter(Rng& g) {
  if (g() % 4 == 0) return 0.0;
  double j = std::ldexp(1.0, -24 + int(g() % 10));
  return g() % 2 ? j : -j;
}

glm::dvec3 centre_of(const Bounds3f& b) {
  return (glm::dvec3(b.lo) + glm::dvec3(b.hi)) * 0.5;
}
double radius_of(const Bounds3f& b) {
  return 0.5 * length(glm::dvec3(b.hi) - glm::dvec3(b.lo));
}

// Per kind: append one random primitive of size ~`scale` at `c`, and aim a ray from `o` at
// the part of the primitive where hit and miss meet (silhouette, edge, rim).
template <class Kind>
struct Shapes;

template <>
struct Shapes<Sphere> {
  static bool add(Scene& s, Rng& g, glm::dvec3 c, double scale) {
    std::array<double, 4> p{c.x, c.y, c.z, scale * uniform(g, 0.3, 1)};
    return !s.table<Sphere>().append(p, 0).has_value();
  }
  static glm::dvec3 plane_normal(const Scene&, uint32_t, Rng& g) { return unit_vector(g); }
  // A tangent from o: the line's distance from the centre is r(1 + jitter).
  static glm::dvec3 edge_direction(const Scene& s, uint32_t row, const glm::dvec3& o, Rng& g) {
    const auto& t = s.table<Sphere>();
    glm::dvec3 to_c = glm::dvec3(t.center(row)) - o;
    double dist = length(to_c), sin_a = t.r[row] * (1 + band_jitter(g)) / dist;
    if (!(sin_a < 1)) return to_c;
    glm::dvec3 c_hat = to_c / dist;
    return c_hat * std::sqrt(1 - sin_a * sin_a) + orthogonal_unit(g, c_hat) * sin_a;
  }
};

// A moving sphere: the motion is 0 one time in four (the ends equal: the static sphere at every
// time), else up to 4 radii; each ray has its own time (times per lane), and the aimed rays are
// tangent to the sphere where it is at that time, so the band is populated at every time.
template <>
struct Shapes<MovingSphere> {
  static bool add(Scene& s, Rng& g, glm::dvec3 c, double scale) {
    double r = scale * uniform(g, 0.3, 1);
    glm::dvec3 m = g() % 4 == 0 ? glm::dvec3(0, 0, 0) : unit_vector(g) * (r * uniform(g, 0, 4));
    std::array<double, 7> p{c.x, c.y, c.z, c.x + m.x, c.y + m.y, c.z + m.z, r};
    return !s.table<MovingSphere>().append(p, 0).has_value();
  }
  static glm::dvec3 plane_normal(const Scene&, uint32_t, Rng& g) { return unit_vector(g); }
  static glm::dvec3 edge_direction(const Scene& s, uint32_t row, const glm::dvec3& o, Rng& g,
                                   double time) {
    const auto& t = s.table<MovingSphere>();
    glm::dvec3 to_c = t.center_at(row, time) - o;
    double dist = length(to_c), sin_a = t.r[row] * (1 + band_jitter(g)) / dist;
    if (!(sin_a < 1)) return to_c;
    glm::dvec3 c_hat = to_c / dist;
    return c_hat * std::sqrt(1 - sin_a * sin_a) + orthogonal_unit(g, c_hat) * sin_a;
  }
};

// Whether a kind's rays carry times: a moving kind's do.
template <class Kind>
constexpr bool kMoves = std::is_same_v<Kind, MovingSphere>;

// A ray's time: the shutter's ends and middle, and random times in between.
float ray_time(Rng& g, int i) {
  constexpr float kTimes[] = {0.0f, 0.5f, 0x1.fffffep-1f};
  return i % 4 < 3 ? kTimes[i % 4] : float(uniform(g, 0, 1));
}

template <>
struct Shapes<Box> {
  static bool add(Scene& s, Rng& g, glm::dvec3 c, double scale) {
    std::array<double, 6> p{c.x, c.y, c.z};
    for (int k = 0; k < 3; ++k)
      p[3 + k] = scale * uniform(g, 0.2, 1) * (g() % 2 ? 1 : -1);
    return !s.table<Box>().append(p, 0).has_value();
  }
  static glm::dvec3 plane_normal(const Scene&, uint32_t, Rng& g) {
    glm::dvec3 n(0, 0, 0);
    n[int(g() % 3)] = 1;
    return n;
  }
  // At a point of an edge (a corner one time in eight), moved by the jitter.
  static glm::dvec3 edge_direction(const Scene& s, uint32_t row, const glm::dvec3& o, Rng& g) {
    const auto& t = s.table<Box>();
    glm::dvec3 lo(t.lo(row)), hi(t.hi(row)), p;
    int along = int(g() % 4);  // 3: a corner
    for (int k = 0; k < 3; ++k)
      p[k] = k == along ? uniform(g, lo[k], hi[k]) : (g() % 2 ? lo[k] : hi[k]);
    p = p + unit_vector(g) * (band_jitter(g) * length(p - o));
    return p - o;
  }
};

template <>
struct Shapes<Cylinder> {
  static bool add(Scene& s, Rng& g, glm::dvec3 c, double scale) {
    glm::dvec3 a = unit_vector(g) * (scale * uniform(g, 0.5, 2));
    std::array<double, 7> p{c.x, c.y, c.z, a.x, a.y, a.z, scale * uniform(g, 0.1, 0.6)};
    return !s.table<Cylinder>().append(p, 0).has_value();
  }
  static glm::dvec3 plane_normal(const Scene& s, uint32_t row, Rng&) {
    return normalize(glm::dvec3(s.table<Cylinder>().axis(row)));
  }
  // Half the time a tangent to the side (docs/hard-cases.md C5): in the plane across the axis the
  // line touches the circle of radius r(1 + jitter), and it climbs so that it touches at a height
  // inside the caps. Otherwise aimed at a rim point (C3).
  static glm::dvec3 edge_direction(const Scene& s, uint32_t row, const glm::dvec3& o, Rng& g) {
    const auto& t = s.table<Cylinder>();
    glm::dvec3 b(t.base(row)), axis(t.axis(row)), u = normalize(axis);
    double h = length(axis), r = t.r[row];
    glm::dvec3 f = o - b;
    double fa = dot(f, u);
    glm::dvec3 perp = f - u * fa;
    double rho = length(perp);
    if (g() % 2 == 0 || !(rho > 1.01 * r)) {
      glm::dvec3 rim = b + u * (g() % 2 ? h : 0.0) + orthogonal_unit(g, u) * r;
      return rim - o;
    }
    glm::dvec3 out = perp / rho, side = cross(u, out);
    double sin_b = r * (1 + band_jitter(g)) / rho, cos_b = std::sqrt(1 - sin_b * sin_b);
    glm::dvec3 e = out * -cos_b + side * (g() % 2 ? sin_b : -sin_b);
    double run = std::sqrt(rho * rho - r * r), climb = uniform(g, 0.1, 0.9) * h - fa;
    return e * run + u * climb;
  }
};

template <>
struct Shapes<Triangle> {
  static bool add(Scene& s, Rng& g, glm::dvec3 c, double scale) {
    std::array<glm::vec3, 3> p{};
    for (auto& v : p)
      v = glm::vec3(c + unit_vector(g) * (scale * uniform(g, 0.3, 1)));
    glm::dvec3 n = cross(glm::dvec3(p[1]) - glm::dvec3(p[0]), glm::dvec3(p[2]) - glm::dvec3(p[0]));
    if (!(length(n) > 0)) return false;
    glm::vec3 nf(normalize(n));
    s.table<Triangle>().append(p, {nf, nf, nf}, 0);
    return true;
  }
  static glm::dvec3 plane_normal(const Scene& s, uint32_t row, Rng&) {
    const auto& t = s.table<Triangle>();
    return normalize(cross(glm::dvec3(t.p1(row)) - glm::dvec3(t.p0(row)),
                           glm::dvec3(t.p2(row)) - glm::dvec3(t.p0(row))));
  }
  // At a point of an edge or at a vertex (docs/hard-cases.md T1, T3), moved by the jitter.
  static glm::dvec3 edge_direction(const Scene& s, uint32_t row, const glm::dvec3& o, Rng& g) {
    const auto& t = s.table<Triangle>();
    glm::dvec3 v[3] = {glm::dvec3(t.p0(row)), glm::dvec3(t.p1(row)), glm::dvec3(t.p2(row))};
    int k = int(g() % 3);
    double a = g() % 5 == 0 ? 0.0 : uniform(g, 0, 1);
    glm::dvec3 p = v[k] * (1 - a) + v[(k + 1) % 3] * a;
    p = p + unit_vector(g) * (band_jitter(g) * length(p - o));
    return p - o;
  }
};

// ---- Ray sets ----

// A ray that crosses the primitive's plane (triangle, cap, box face) near `aim` at an angle of
// 10^-1 … 10^-4 rad: t is ill-conditioned there (docs/hard-cases.md §0, T8, C4).
Rayd grazing_ray(const glm::dvec3& aim, const glm::dvec3& n, double dist, Rng& g) {
  double angle = std::pow(10.0, uniform(g, -4, -1)) * (g() % 2 ? 1 : -1);
  glm::dvec3 d = orthogonal_unit(g, n) * std::cos(angle) + n * std::sin(angle);
  glm::dvec3 o(glm::vec3(aim - d * dist));
  return {o, normalize(aim - o)};
}

// Rays, each from a float origin at 2–20 sizes from one primitive (one in three from 10^2 …
// 10^4 sizes: far, small shapes, docs/hard-cases.md S1 and C5): 2 in 5 toward a random
// point around it, 3 in 10 aimed at its band, 1 in 10 from inside it (the far root of a
// solid, docs/hard-cases.md S5), 1 in 5 grazing its plane. One in five has a
// finite tmax near the primitive and one in ten a tmin near it, so that the (tmin, tmax) range
// decides too. Every 29th ray is invalid.
template <class Kind>
std::vector<Rayd> make_rays(const Scene& s, Rng& g, int n) {
  const auto& table = s.table<Kind>();
  std::vector<Rayd> rays;
  for (int i = 0; i < n; ++i) {
    uint32_t row = uint32_t(g() % table.size());
    const float time = kMoves<Kind> ? ray_time(g, i / 5) : 0.5f;
    Bounds3f b = table.bounds(row);
    glm::dvec3 c = centre_of(b);
    double size = radius_of(b);
    double dist = size * (i % 3 ? uniform(g, 2, 20) : std::pow(10.0, uniform(g, 2, 4)));
    glm::dvec3 o(glm::vec3(c + unit_vector(g) * dist)), around = c + unit_vector(g) * (0.6 * size);
    Rayd r;
    if (i % 5 == 4)
      r = grazing_ray(around, Shapes<Kind>::plane_normal(s, row, g), dist, g);
    else if (i % 10 == 7)
      r = {glm::dvec3(glm::vec3(c + unit_vector(g) * (0.3 * size))),
           unit_vector(g)};  // from inside
    else if (i % 5 >= 2) {
      if constexpr (kMoves<Kind>)
        r = {o, normalize(Shapes<Kind>::edge_direction(s, row, o, g, time))};
      else
        r = {o, normalize(Shapes<Kind>::edge_direction(s, row, o, g))};
    } else
      r = {o, normalize(c + unit_vector(g) * (1.2 * size * std::cbrt(uniform(g, 0, 1))) - o)};
    o = r.o;
    if (i % 5 == 1) r.tmax = length(c - o) * uniform(g, 0.8, 1.2);
    if (i % 10 == 3) r.tmin = length(c - o) * uniform(g, 0.8, 1.2);
    r.time = time;
    rays.push_back(round_to_float(r));
  }
  const double nan = std::nan("");
  for (std::size_t i = 7; i < rays.size(); i += 29) {
    switch ((i / 29) % 5) {
      case 0:
        rays[i].o.y = nan;
        break;
      case 1:
        rays[i].d = {0, 0, 0};
        break;
      case 2:
        rays[i].tmin = 2 * rays[i].tmax + 1;
        break;
      case 3:
        rays[i].tmax = nan;
        break;
      default:
        rays[i].d.x = INFINITY;
        break;
    }
  }
  return rays;
}

// One primitive at the offset, or a small random set of them around it.
template <class Kind>
Scene make_scene(Rng& g, glm::dvec3 offset, double scale, int count) {
  Scene s;
  s.materials.push_back(Material{});
  for (int tries = 0; int(s.table<Kind>().size()) < count && tries < 10 * count; ++tries) {
    glm::dvec3 c = count == 1 ? offset : offset + unit_vector(g) * (3 * scale * uniform(g, 0, 1));
    Shapes<Kind>::add(s, g, c, scale);
  }
  return s;
}

// ---- The comparison ----

struct Tally {
  long count[3] = {0, 0, 0};    // by RayClass
  long band_disagreements = 0;  // hit/miss or primitive differs from the reference
  double max_t_over_bound = 0;  // over clear hits: |t − t_ref| / bound
  double max_flip_ratio = 0;    // over band disagreements: |margin| / bound (≤ 1)
  uint64_t max_t_ulps = 0;      // over clear hits: the error in ulps (large on grazing rays)
  long failures = 0;
};

// The assertions of §0 for one ray: in the clear classes the kernel gives the reference's
// answer (the same primitive, t within the bound), and occlusion agrees with the closest hit;
// in the band either answer, but no NaN. The classifier itself must agree with the reference.
void check_ray(const Rayd& ray, const RayVerdict& v, const Hit& ref, float t, uint32_t prim,
               uint32_t occluded, Tally& tally) {
  const bool found = prim != PrimRef::kInvalidBits;
  ++tally.count[int(v.cls)];
  bool ok = !std::isnan(t);
  if (v.cls == RayClass::kClearHit) {
    double err = std::abs(double(t) - v.t);
    ok = ok && found && prim == v.prim.bits() && err <= v.t_bound && ref.prim == v.prim;
    if (found && v.t_bound > 0)
      tally.max_t_over_bound = std::max(tally.max_t_over_bound, err / v.t_bound);
    if (found) tally.max_t_ulps = std::max(tally.max_t_ulps, ulp_distance(t, float(v.t)));
  } else if (v.cls == RayClass::kClearMiss) {
    ok = ok && !found && !ref.hit();
  } else if (found != ref.hit() || (found && prim != ref.prim.bits())) {
    ++tally.band_disagreements;
    tally.max_flip_ratio = std::max(tally.max_flip_ratio, v.band_ratio);
  }
  if (v.cls != RayClass::kBand) ok = ok && (occluded == 0) == found;
  if (!ok && tally.failures++ < 8)
    ADD_FAILURE() << testing::ray_class_name(v.cls) << " ray o=(" << ray.o.x << ", " << ray.o.y
                  << ", " << ray.o.z << ") d=(" << ray.d.x << ", " << ray.d.y << ", " << ray.d.z
                  << ") tmin " << ray.tmin << " tmax " << ray.tmax << ": kernel t " << t << " prim "
                  << prim << " occluded " << (occluded == 0) << "; classified t " << v.t << " ± "
                  << v.t_bound << " prim " << v.prim.bits() << "; reference t " << ref.t << " prim "
                  << ref.prim.bits();
}

// Builds the BVH (which reorders the rows), classifies every ray once, then traces the stream along
// every path and checks each answer.
void check_scene(Scene& s, const std::vector<Rayd>& rays, const std::vector<KernelPath>& paths,
                 std::vector<Tally>& tallies) {
  Bvh bvh = build_bvh_and_reorder(s, {.wide_nodes = true});
  std::vector<RayVerdict> verdicts(rays.size());
  std::vector<Hit> refs(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    verdicts[i] = classify_closest(s, rays[i]);
    refs[i] = closest_hit_ref(s, rays[i]);
    // The far-bounds shortcut (used on large scenes) must not change any verdict.
    RayVerdict quick = classify_closest(s, rays[i], /*skip_far_bounds=*/true);
    EXPECT_TRUE(quick.cls == verdicts[i].cls && quick.prim == verdicts[i].prim) << i;
  }
  RayStream stream = RayStream::from(rays);
  for (std::size_t p = 0; p < paths.size(); ++p) {
    SCOPED_TRACE(paths[p].name);
    HitStream closest, occluded;
    trace_closest(paths[p], s, bvh, stream, closest);
    trace_occluded(paths[p], s, bvh, stream, occluded);
    for (std::size_t i = 0; i < rays.size(); ++i)
      check_ray(rays[i], verdicts[i], refs[i], closest.t[i], closest.prim[i], occluded.prim[i],
                tallies[p]);
  }
}

// Offsets and scales of docs/hard-cases.md §0. A scale below 64 ulps of the offset is skipped:
// boxes that thin do not survive rounding to float (BoxTable::append refuses them).
struct Placement {
  double offset, scale;
};
std::vector<Placement> placements() {
  std::vector<Placement> out;
  for (double offset : {0.0, 1e2, 1e4, 1e5})
    for (double scale : {1e-3, 1.0, 1e3})
      if (scale >= 64 * std::ldexp(1.0, std::ilogb(std::max(offset, 1.0)) - 23))
        out.push_back({offset, scale});
  return out;
}

template <class Kind>
class KernelBandTest : public ::testing::Test {};

using Kinds = ::testing::Types<Sphere, Box, Cylinder, Triangle, MovingSphere>;
struct KindNames {
  template <class Kind>
  static std::string GetName(int) {
    return std::string(Kind::name);
  }
};
TYPED_TEST_SUITE(KernelBandTest, Kinds, KindNames);

// 16·k + 7 rays per stream: the last packet has inactive lanes at every width, and the
// invalid rays inside the stream make inactive lanes in full packets.
TYPED_TEST(KernelBandTest, ClearClassesAgreeWithTheReference) {
  using Kind = TypeParam;
  const std::vector<KernelPath> paths = kernel_paths();
  std::vector<Tally> tallies(paths.size());
  Rng g(2026 + int(tag_of<Kind>));
  for (const Placement& at : placements())
    for (int count : {1, 6}) {
      SCOPED_TRACE(::testing::Message() << "offset " << at.offset << ", scale " << at.scale << ", "
                                        << count << " primitives");
      glm::dvec3 offset(at.offset, -at.offset, at.offset);
      Scene s = make_scene<Kind>(g, offset, at.scale, count);
      ASSERT_GT(s.table<Kind>().size(), 0u);
      check_scene(s, make_rays<Kind>(s, g, 16 * 500 + 7), paths, tallies);
    }
  for (std::size_t p = 0; p < paths.size(); ++p) {
    const Tally& t = tallies[p];
    std::string summary =
        (::testing::Message() << "clear hit " << t.count[0] << ", clear miss " << t.count[1]
                              << ", band " << t.count[2] << " (disagreeing " << t.band_disagreements
                              << ", deepest at " << t.max_flip_ratio << " of the bound)"
                              << "; max |t - t_ref| / bound " << t.max_t_over_bound << " (max "
                              << t.max_t_ulps << " ulp)")
            .GetString();
    std::printf("[ bands    ] %s %s: %s\n", KindNames::GetName<Kind>(0).c_str(),
                paths[p].name.c_str(), summary.c_str());
    ::testing::Test::RecordProperty(paths[p].name, summary);
    EXPECT_GT(t.count[2], 0) << "no ray reached the band: the aimed rays do not test it";
    EXPECT_GT(t.count[0], t.count[2]);
    EXPECT_GT(t.count[1], t.count[2]);
  }
}

}  // namespace
}  // namespace raylane
