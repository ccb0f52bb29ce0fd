// The speed-versus-error table of the packet kernels (docs/benchmarks.md, "Kernel accuracy"): for
// each primitive kind, on random inputs and on the hard cases of docs/hard-cases.md, and for each
// instruction set, the distribution of the hit distance's error against the double reference (run
// on the same float inputs, converted exactly: docs/hard-cases.md §0), hit/miss disagreements, and
// the speed of the packet tracer on that ray set. Each ray is classified by the error bounds of
// tests/support/error_bands (compiled into this program): "in band" counts the rays whose
// answer rounding may flip, "flips outside band" the disagreements on clear rays (kernel bugs),
// and the last column how much of its t bound a clear hit's error uses.
//
//   build/bench/kernel_accuracy [rays per set, default 131072]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "raylane/bvh/bvh.h"
#include "raylane/core/float_util.h"
#include "raylane/core/parallel.h"
#include "raylane/simd/isa.h"
#include "raylane/trace/brute_force.h"
#include "raylane/trace/simd_tracer.h"
#include "support/error_bands.h"

namespace raylane::bench {
namespace {

constexpr int kPrims = 64;  // primitives per set, far apart, each aimed at by its share of rays

using Rng = std::mt19937_64;
double uniform(Rng& g, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(g);
}
glm::dvec3 unit(Rng& g) {
  double z = uniform(g, -1, 1), phi = uniform(g, 0, 2 * M_PI), s = std::sqrt(1 - z * z);
  return {s * std::cos(phi), s * std::sin(phi), z};
}

// A set: the scene's primitives and, for primitive i, where rays aim (a point c + s·axis,
// s ∈ [−0.55, 0.55], moved up to `jitter` in a random direction: about half hit, some graze)
// and the distance from which they start.
struct Target {
  glm::dvec3 c{}, axis{};
  double jitter, distance;
};
struct InputSet {
  std::string kind, name;
  Scene scene;
  std::vector<Target> targets;
};

// Places primitive i of a set on a coarse grid, so rays aimed at one rarely meet another.
glm::dvec3 slot(int i, double spacing, double offset) {
  return glm::dvec3(i % 4, (i / 4) % 4, i / 16) * spacing + glm::dvec3(offset, offset, offset);
}

InputSet spheres(const std::string& name, bool far, double offset) {
  InputSet s{"sphere", name, {}, {}};
  s.scene.materials.push_back(Material::default_grey());
  Rng g(1);
  for (int i = 0; i < kPrims; ++i) {
    double r = far ? std::pow(10.0, uniform(g, -2, 2)) : uniform(g, 0.5, 2);
    glm::dvec3 c = slot(i, far ? 400 : 8, offset);
    double p[4] = {c.x, c.y, c.z, r};
    s.scene.table<Sphere>().append(std::span<const double, 4>(p), 0);
    // S1: distance/r in decades 1e1 … 1e5 for the far set.
    s.targets.push_back(
        {c, {}, 1.1 * r, far ? r * std::pow(10.0, uniform(g, 1, 5)) : uniform(g, 3, 20)});
  }
  return s;
}

InputSet boxes(const std::string& name, double offset) {
  InputSet s{"box", name, {}, {}};
  s.scene.materials.push_back(Material::default_grey());
  Rng g(2);
  for (int i = 0; i < kPrims; ++i) {
    glm::dvec3 c = slot(i, 8, offset);
    double p[6] = {c.x, c.y, c.z, uniform(g, -2, 2), uniform(g, 0.1, 2), uniform(g, -2, -0.1)};
    s.scene.table<Box>().append(std::span<const double, 6>(p), 0);
    s.targets.push_back({c + glm::dvec3(p[3], p[4], p[5]) * 0.5, {}, 1.5, uniform(g, 3, 20)});
  }
  return s;
}

InputSet cylinders(const std::string& name, bool thin_far, double offset) {
  InputSet s{"cylinder", name, {}, {}};
  s.scene.materials.push_back(Material::default_grey());
  Rng g(3);
  for (int i = 0; i < kPrims; ++i) {
    glm::dvec3 b = slot(i, thin_far ? 40 : 8, offset), a = unit(g) * (thin_far ? 10.0 : 2.0);
    double r = thin_far ? 1e-3 : uniform(g, 0.3, 1.0);
    double p[7] = {b.x, b.y, b.z, a.x, a.y, a.z, r};
    s.scene.table<Cylinder>().append(std::span<const double, 7>(p), 0);
    // C5: distance/r ~ 1e6 for the thin set.
    s.targets.push_back({b + a * 0.5, a, 1.3 * r, thin_far ? 1e3 : uniform(g, 3, 20)});
  }
  return s;
}

InputSet triangles(const std::string& name, double size, double offset) {
  InputSet s{"triangle", name, {}, {}};
  s.scene.materials.push_back(Material::default_grey());
  Rng g(4);
  for (int i = 0; i < kPrims; ++i) {
    glm::dvec3 c = slot(i, 8 * std::max(size, 1.0), offset);
    glm::vec3 p[3], n = glm::vec3(0, 0, 1);
    for (auto& v : p)
      v = glm::vec3(c + unit(g) * size);
    s.scene.table<Triangle>().append({p[0], p[1], p[2]}, {n, n, n}, 0);
    glm::dvec3 centroid = (glm::dvec3(p[0]) + glm::dvec3(p[1]) + glm::dvec3(p[2])) / 3.0;
    s.targets.push_back({centroid, {}, size, uniform(g, 3, 20) * size});
  }
  return s;
}

// Rays from a random direction at each target's distance toward its aim point.
std::vector<Rayd> make_rays(const InputSet& s, int count) {
  Rng g(5);
  std::vector<Rayd> rays;
  for (int i = 0; i < count; ++i) {
    const Target& t = s.targets[std::size_t(i % kPrims)];
    glm::dvec3 aim =
        t.c + t.axis * uniform(g, -0.55, 0.55) + unit(g) * (t.jitter * std::cbrt(uniform(g, 0, 1)));
    glm::dvec3 o = t.c + unit(g) * t.distance;
    rays.push_back(ray_cast<double>(ray_cast<float>(Rayd{o, normalize(aim - o)})));
  }
  return rays;
}

struct Row {
  double mrays = 0;
  std::size_t hits = 0, false_miss = 0, false_hit = 0, other_prim = 0;
  std::size_t band = 0;                // rays whose answer the error bounds leave open
  std::size_t flips_outside_band = 0;  // hit/miss or primitive differs on a clear ray: a bug
  double max_t_over_bound = 0;         // over clear hits: |t − t_ref| / the ray's t bound
  std::vector<double> ulps, rel;
};

double percentile(std::vector<double>& v, double p) {
  if (v.empty()) return 0;
  std::size_t i = std::min(v.size() - 1, std::size_t(p * double(v.size())));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(i), v.end());
  return v[i];
}

Row measure(const InputSet& s, const Bvh& bvh, const std::vector<Rayd>& rays,
            const std::vector<Hit>& ref, const std::vector<testing::RayVerdict>& verdicts,
            Isa isa) {
  RayStream stream = RayStream::from(rays);
  SimdTracer tracer(isa);
  HitStream hits;
  hits.resize(stream.size());
  std::vector<double> seconds;
  for (int rep = 0; rep < 5; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    parallel_chunks(stream.size(), kTraceChunk, [&](std::size_t begin, std::size_t end) {
      tracer.trace_range(s.scene, bvh, stream, begin, end, hits, /*any_hit=*/false);
    });
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  Row row;
  row.mrays = double(rays.size()) / percentile(seconds, 0.5) * 1e-6;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    bool hit = hits.prim[i] != PrimRef::kInvalidBits;
    const testing::RayVerdict& v = verdicts[i];
    bool same = ref[i].hit() == hit && (!hit || hits.prim[i] == ref[i].prim.bits());
    row.band += v.cls == testing::RayClass::kBand;
    row.flips_outside_band += v.cls != testing::RayClass::kBand && !same;
    if (v.cls == testing::RayClass::kClearHit && hit && v.t_bound > 0)
      row.max_t_over_bound =
          std::max(row.max_t_over_bound, std::abs(double(hits.t[i]) - v.t) / v.t_bound);
    if (ref[i].hit() != hit) ++(hit ? row.false_hit : row.false_miss);
    if (!(ref[i].hit() && hit)) continue;
    ++row.hits;
    // Another primitive: the float kernel missed a grazed one and hit the next (or the
    // reverse); t is not comparable.
    if (hits.prim[i] != ref[i].prim.bits()) {
      ++row.other_prim;
      continue;
    }
    float t_ref = float(ref[i].t);
    row.ulps.push_back(double(ulp_distance(hits.t[i], t_ref)));
    row.rel.push_back(std::abs(hits.t[i] - ref[i].t) / ref[i].t);
  }
  return row;
}

void print_set(InputSet& s, int count) {
  Bvh bvh = build_bvh_and_reorder(s.scene);
  std::vector<Rayd> rays = make_rays(s, count);
  std::vector<Hit> ref(rays.size());
  std::vector<testing::RayVerdict> verdicts(rays.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::ptrdiff_t i = 0; i < std::ptrdiff_t(rays.size()); ++i) {
    ref[i] = closest_hit_ref(s.scene, rays[i]);
    verdicts[i] = testing::classify_closest(s.scene, rays[i], /*skip_far_bounds=*/true);
  }
  for (Isa isa : supported_isas()) {
    Row r = measure(s, bvh, rays, ref, verdicts, isa);
    std::printf(
        "| %s | %s | %s | %.1f | %zu | %zu | %zu | %zu | %zu | %zu | %.1f | %.1f | %.0f | %.1e | "
        "%.2f |\n",
        s.kind.c_str(), s.name.c_str(), std::string(isa_name(isa)).c_str(), r.mrays, r.hits,
        r.false_miss, r.false_hit, r.band, r.flips_outside_band, r.other_prim,
        percentile(r.ulps, 0.5), percentile(r.ulps, 0.99), percentile(r.ulps, 1.0),
        percentile(r.rel, 1.0), r.max_t_over_bound);
  }
}

}  // namespace
}  // namespace raylane::bench

int main(int argc, char** argv) {
  using namespace raylane::bench;
  int count = argc > 1 ? std::atoi(argv[1]) : 1 << 17;
  if (count < kPrims) {
    std::fprintf(stderr, "usage: kernel_accuracy [rays per set ≥ %d]\n", kPrims);
    return 2;
  }
  std::printf(
      "Hit distance t of the packet kernels against the double reference, %d rays per "
      "set; errors over rays that hit the same primitive (ulps of the reference t in float).\n\n",
      count);
  std::printf(
      "| kind | set | ISA | Mrays/s | both hit | false miss | false hit | in band | flips "
      "outside band | other prim | median ulp | p99 ulp | max ulp | max rel. err | max t err / "
      "bound |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<InputSet> sets;
  sets.push_back(spheres("random", false, 0));
  sets.push_back(spheres("far small (S1)", true, 0));
  sets.push_back(boxes("random", 0));
  sets.push_back(boxes("offset 1e5 (B7)", 1e5));
  sets.push_back(cylinders("random", false, 0));
  sets.push_back(cylinders("thin far (C5)", true, 0));
  sets.push_back(triangles("random", 1, 0));
  sets.push_back(triangles("offset 1e5", 1, 1e5));
  sets.push_back(triangles("tiny 1e-4 (T5)", 1e-4, 0));
  for (InputSet& s : sets)
    print_set(s, count);
  return 0;
}
