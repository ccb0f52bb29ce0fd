// The arrivals' sort in lanes (render/arrival_lanes.h) against arrival_of, ray by ray, at every
// instruction set this CPU has: random wavefronts of hits on several kinds, misses with and
// without an environment, emitters, materials shaded in lanes and in double, paths below, at
// and past the last bounce, the double shading's call (no route shaded in lanes), and every
// length from 0 to past two registers, so that each lane of a last partial batch is met.
#include "raylane/render/arrival_lanes.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "raylane/core/strings.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sobol.h"
#include "raylane/scene/parser.h"
#include "support/paths.h"

namespace raylane {
namespace {

// Routes as LaneMaterials numbers them (the kernel takes any numbers).
constexpr uint32_t kEmitter = 0, kLanes = 1, kDouble = 2, kNone = 3;

struct Wavefront {
  std::vector<uint32_t> prim, ray_path, depth;
  std::array<std::vector<double>, 3> beta;
  std::array<std::vector<uint32_t>, kPrimKindCount> materials;
  std::vector<uint32_t> route;

  ArrivalColumns columns(bool environment, bool lanes) const {
    ArrivalColumns in;
    in.prim = prim.data(), in.ray_path = ray_path.data(), in.count = prim.size();
    in.depth = depth.data();
    in.beta = {beta[0].data(), beta[1].data(), beta[2].data()};
    for (std::size_t t = 0; t < kPrimKindCount; ++t)
      if (!materials[t].empty())
        in.material_of[t] = materials[t].data(), in.rows_of[t] = materials[t].size();
    in.route = route.data(), in.materials = route.size();
    in.emitter_route = kEmitter, in.lanes_route = lanes ? kLanes : kNone;
    in.max_depth = 5, in.environment = environment;
    return in;
  }
};

// n rays of n + 3 paths, hitting kinds 0, 1, 4 and 5 (the others' tables empty), a tenth
// missing, with throughputs that round to float at every distance from a float (and some that
// do not fit one). The kinds' columns and the routes are read by one register, two (at AVX2
// and at AVX-512) or a gather (simd::lookup).
Wavefront random_wavefront(std::size_t n, Rng& rng) {
  Wavefront w;
  const std::size_t paths = n + 3, material_count = 20;
  for (uint32_t m = 0; m < material_count; ++m)
    w.route.push_back(m % 9 < 2 ? kEmitter : m % 9 < 6 ? kLanes : kDouble);
  const std::size_t kinds[4] = {0, 1, 4, 5}, rows[4] = {5, 70, 12, 24};
  for (int j = 0; j < 4; ++j)
    for (std::size_t r = 0; r < rows[j]; ++r)
      w.materials[kinds[j]].push_back(uint32_t(rng.uniform() * material_count));
  for (std::size_t k = 0; k < n; ++k) {
    w.ray_path.push_back(uint32_t(rng.uniform() * double(paths)));
    w.depth.push_back(uint32_t(rng.uniform() * 7));  // 0..6 around the last bounce, 5
    for (auto& c : w.beta)
      c.push_back(rng.uniform() < 0.05 ? 1e39 : rng.uniform() * 3);
    if (rng.uniform() < 0.1) {
      w.prim.push_back(PrimRef::invalid().bits());
      continue;
    }
    const int j = int(rng.uniform() * 4);
    const uint32_t row = uint32_t(rng.uniform() * double(rows[j]));
    w.prim.push_back(PrimRef(PrimTag(kinds[j]), row).bits());
  }
  return w;
}

// Room for n rows rounded up to 16, and the canary past it.
struct Rows {
  std::vector<uint32_t> path, ray, material, depth, rare;
  std::array<std::vector<float>, 3> beta;
  static constexpr float kCanary = -7.5f;
  explicit Rows(std::size_t n) {
    const std::size_t room = (n + 15) / 16 * 16 + 1;
    for (auto* c : {&path, &ray, &material, &depth, &rare})
      c->assign(room, 0xfeedu);
    for (auto& c : beta)
      c.assign(room, kCanary);
  }
  ArrivalRows out() {
    ArrivalRows o;
    o.path = path.data(), o.ray = ray.data(), o.material = material.data();
    o.depth = depth.data(), o.rare = rare.data();
    o.beta = {beta[0].data(), beta[1].data(), beta[2].data()};
    return o;
  }
};

void expect_sorted_as_reference(Isa isa, const Wavefront& w, bool environment, bool lanes) {
  const ArrivalColumns in = w.columns(environment, lanes);
  Rows got(in.count);
  ArrivalRows out = got.out();
  sort_arrival_rows(isa, in, out);
  std::size_t lane = 0, rare = 0;
  for (std::size_t k = 0; k < in.count; ++k) {
    SCOPED_TRACE(cat("ray ", k));
    const Arrival a = arrival_of(in, k);
    if (a == Arrival::kLanes) {
      ASSERT_LT(lane, out.lanes);
      const PrimRef hit = PrimRef::from_bits(w.prim[k]);
      EXPECT_EQ(got.ray[lane], k);
      EXPECT_EQ(got.path[lane], w.ray_path[k]);
      EXPECT_EQ(got.material[lane], w.materials[std::size_t(hit.tag())][hit.row()]);
      EXPECT_EQ(got.depth[lane], w.depth[k]);
      for (std::size_t c = 0; c < 3; ++c)  // rounded to nearest, as a cast rounds
        EXPECT_EQ(got.beta[c][lane], float(w.beta[c][k])) << "component " << c;
      ++lane;
    } else if (a == Arrival::kRare) {
      ASSERT_LT(rare, out.rare_count);
      EXPECT_EQ(got.rare[rare], k);
      ++rare;
    }
  }
  EXPECT_EQ(out.lanes, lane);
  EXPECT_EQ(out.rare_count, rare);
  const std::size_t canary = got.path.size() - 1;
  for (auto* c : {&got.path, &got.ray, &got.material, &got.depth, &got.rare})
    EXPECT_EQ((*c)[canary], 0xfeedu) << "a store past the room";
  for (const auto& c : got.beta)
    EXPECT_EQ(c[canary], Rows::kCanary) << "a store past the room";
}

TEST(ArrivalLanes, SortsEveryRayAsTheReferenceDoes) {
  Rng rng(11);
  for (Isa isa : supported_isas())
    for (std::size_t n : {0, 1, 3, 4, 7, 8, 9, 15, 16, 17, 31, 33, 40, 1001}) {
      const Wavefront w = random_wavefront(n, rng);
      for (bool environment : {false, true})
        for (bool lanes : {true, false}) {
          SCOPED_TRACE(
              cat(isa_name(isa), " rays ", n, " environment ", environment, " lanes ", lanes));
          expect_sorted_as_reference(isa, w, environment, lanes);
        }
    }
}

// The reference's own order of decisions: an emitter ends its path at any depth, a miss
// whatever its path's depth, and a path at the last bounce sends no vertex.
TEST(ArrivalLanes, ReferenceOrdersItsDecisions) {
  Wavefront w;
  w.route = {kEmitter, kLanes, kDouble};
  w.materials[0] = {0, 1, 2};
  w.depth = {5, 5, 5, 5, 4, 4};  // rays 0-3 at the last bounce (max 5), 4 and 5 below it
  w.prim = {PrimRef(PrimTag(0), 0).bits(), PrimRef(PrimTag(0), 1).bits(),
            PrimRef(PrimTag(0), 2).bits(), PrimRef::invalid().bits(),
            PrimRef(PrimTag(0), 1).bits(), PrimRef(PrimTag(0), 2).bits()};
  w.ray_path = {0, 0, 0, 0, 1, 1};
  const ArrivalColumns in = w.columns(true, true);
  const Arrival want[6] = {Arrival::kRare, Arrival::kEnd,   Arrival::kEnd,
                           Arrival::kRare, Arrival::kLanes, Arrival::kRare};
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_EQ(arrival_of(in, k), want[k]) << "ray " << k;
  EXPECT_EQ(arrival_of(w.columns(false, true), 3), Arrival::kEnd);
  EXPECT_EQ(arrival_of(w.columns(true, false), 4), Arrival::kRare);
}

// The lane rows' seeds and survival in lanes against row_path_columns_of, row by row and bit
// for bit, at every instruction set: wavefronts whose every ray is a lane vertex (so the rows
// are the rays), every count from 0 to past two registers and a long one, depths on both sides
// of roulette's first (from depth 0, and from above every depth: no row has it), seeds and
// salts with every bit pattern (the products' cross terms), paths read at a stride.
TEST(ArrivalLanes, RowPathColumnsAreTheReferences) {
  Rng rng(17);
  constexpr uint32_t kStride = 5, kPaths = 300;
  auto bits64 = [&] {
    return uint64_t(rng.uniform() * 0x1p32) << 32 | uint64_t(rng.uniform() * 0x1p32);
  };
  std::vector<uint64_t> seeds(kPaths * kStride, 0x5eed5eed5eed5eedull);
  for (uint32_t p = 0; p < kPaths; ++p)
    seeds[p * kStride] = bits64();
  for (Isa isa : supported_isas())
    for (std::size_t n : {0, 1, 3, 4, 5, 7, 8, 9, 15, 16, 17, 31, 33, 40, 1001})
      for (uint32_t from : {0u, 2u, 0x7fffffffu}) {
        SCOPED_TRACE(cat(isa_name(isa), " rows ", n, " roulette from ", from));
        Wavefront w;
        w.route = {kLanes};
        w.materials[0] = {0};
        for (std::size_t k = 0; k < n; ++k) {
          w.prim.push_back(PrimRef(PrimTag(0), 0).bits());
          w.ray_path.push_back(uint32_t(rng.uniform() * kPaths));
          w.depth.push_back(k % 7 == 3 ? 0x70000000u + uint32_t(k) : uint32_t(rng.uniform() * 5));
          for (auto& c : w.beta)
            c.push_back(1.0);
        }
        ArrivalColumns in = w.columns(false, true);
        in.max_depth = 0x7fffffffu;
        in.pixel_seed = seeds.data(), in.seed_stride = kStride;
        in.light_salt = bits64(), in.salt_step = bits64(), in.bsdf_offset = bits64();
        in.roulette_from = from, in.survival = 0.8f;
        Rows got(n);
        ArrivalRows out = got.out();
        const std::size_t room = got.path.size();
        std::vector<uint64_t> light(room, 7), bsdf(room, 7);
        std::vector<float> survival(room, -1.0f);
        out.light_seed = light.data(), out.bsdf_seed = bsdf.data(), out.survival = survival.data();
        sort_arrival_rows(isa, in, out);
        ASSERT_EQ(out.lanes, n);
        std::vector<uint64_t> want_light(n), want_bsdf(n);
        std::vector<float> want_survival(n);
        ArrivalRows ref = out;
        ref.light_seed = want_light.data(), ref.bsdf_seed = want_bsdf.data();
        ref.survival = want_survival.data();
        bool want_any = false;
        for (std::size_t r = 0; r < n; ++r)
          want_any = row_path_columns_of(in, ref, r) || want_any;
        EXPECT_EQ(out.any_roulette, want_any);
        for (std::size_t r = 0; r < n; ++r) {
          ASSERT_EQ(light[r], want_light[r]) << "row " << r;
          ASSERT_EQ(bsdf[r], want_bsdf[r]) << "row " << r;
          ASSERT_EQ(survival[r], want_survival[r]) << "row " << r;
        }
        EXPECT_TRUE(light[n] == 7 && bsdf[n] == 7 && survival[n] == -1.0f) << "past the rows";
      }
}

// The salts the render passes (src/render/wavefront/arrival.cpp: group_salt of the light and
// BSDF groups at depths 0 and 1) are group_salt's of the rows' groups at every depth, as
// row_path_columns_of makes them.
TEST(ArrivalLanes, RowSaltsAreTheGroupsSalts) {
  const uint64_t seed = 0x0123456789abcdefull;
  const uint32_t path = 0;
  ArrivalColumns in;
  in.pixel_seed = &seed;
  in.light_salt = group_salt(1), in.salt_step = group_salt(3) - group_salt(1);
  in.bsdf_offset = group_salt(2) - group_salt(1);
  for (uint32_t d : {0u, 1u, 7u, 63u, 100000u}) {
    uint64_t light, bsdf;
    float survival;
    ArrivalRows out;
    out.path = const_cast<uint32_t*>(&path), out.depth = &d;
    out.light_seed = &light, out.bsdf_seed = &bsdf, out.survival = &survival;
    row_path_columns_of(in, out, 0);
    EXPECT_EQ(light, seed ^ group_salt(1 + 2 * d)) << d;
    EXPECT_EQ(bsdf, seed ^ group_salt(2 + 2 * d)) << d;
  }
}

// The render's material columns (set_material_columns) give every row a hit can name the
// material Scene::material_of gives it, through the lanes' short-column permutes and gathers:
// on scenes of spheres, boxes, cylinders and triangles, of CSG (whose material column counts
// leaves, not blocks) and of SDFs, at every instruction set.
TEST(ArrivalLanes, MaterialsAreTheScenes) {
  for (const char* file : {"scenes/testscene.scn", "scenes/csg.scn", "scenes/sdf.scn"}) {
    auto p = load_scene_file(testing::source_path(file));
    ASSERT_TRUE(p.ok()) << file;
    const Scene& scene = p.scene;
    ArrivalColumns in;
    set_material_columns(scene, in);
    std::vector<uint32_t> prim, want, route(scene.materials.size(), kLanes);
    PrimKinds::for_each([&](auto kind) {  // every row a hit can name: a CSG hit names its leaf
      using Kind = decltype(kind);
      for (std::size_t r = 0; r < scene.table<Kind>().material.size(); ++r) {
        prim.push_back(PrimRef(tag_of<Kind>, uint32_t(r)).bits());
        want.push_back(scene.material_of(PrimRef::from_bits(prim.back())));
      }
    });
    ASSERT_FALSE(prim.empty()) << file;
    const std::vector<uint32_t> zeros(prim.size(), 0);
    const std::array<std::vector<double>, 3> ones{std::vector<double>(prim.size(), 1.0),
                                                  std::vector<double>(prim.size(), 1.0),
                                                  std::vector<double>(prim.size(), 1.0)};
    in.prim = prim.data(), in.ray_path = zeros.data(), in.depth = zeros.data();
    in.count = prim.size();
    in.beta = {ones[0].data(), ones[1].data(), ones[2].data()};
    in.route = route.data(), in.materials = route.size();
    in.emitter_route = kEmitter, in.lanes_route = kLanes, in.max_depth = 1;
    for (Isa isa : supported_isas()) {
      SCOPED_TRACE(cat(file, " ", isa_name(isa)));
      Rows got(prim.size());
      ArrivalRows out = got.out();
      sort_arrival_rows(isa, in, out);
      ASSERT_EQ(out.lanes, prim.size());
      for (std::size_t k = 0; k < prim.size(); ++k)
        ASSERT_EQ(got.material[k], want[k]) << "row " << k << " of kind " << (prim[k] >> 29);
    }
  }
}

}  // namespace
}  // namespace raylane
