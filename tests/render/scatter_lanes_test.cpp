// scatter_vertices (render/vertex_lanes.h: the BSDF and the steps after it in one pass, the rays
// packed into their queues as they are made) against shade_lanes then finish_vertices, bit for
// bit at every instruction set this CPU has; and its one light taken as broadcast lanes.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstring>
#include <limits>
#include <vector>

#include "raylane/core/strings.h"
#include "raylane/render/vertex_lanes.h"
#include "support/same_bits.h"
#include "support/vertex_rows.h"

namespace raylane {
namespace {

using namespace testing;  // same_bits, the random vertices (support/vertex_rows.h)

// A scatter kernel's queues, each destination with `room` values and canaries after them.
struct Queues {
  static constexpr uint32_t kCanary = 0xdeadbeefu;
  std::array<std::vector<float>, 3> next_o, next_d, shadow_o, shadow_d, next_prev_p;
  std::vector<float> shadow_tmax;
  std::vector<uint32_t> next_path, shadow_path, shadow_light, next_depth;
  std::array<std::vector<double>, 3> shadow_c, next_beta;
  std::vector<double> next_prev_pdf;
  std::size_t room;
  VertexQueues q;

  Queues(std::size_t room, std::size_t canaries, const uint32_t* path, const uint32_t* depth)
      : room(room) {
    const std::size_t n = room + canaries;
    const float f = std::bit_cast<float>(kCanary);
    const double d = std::bit_cast<double>(uint64_t(kCanary));
    for (auto* c : {&next_o, &next_d, &shadow_o, &shadow_d, &next_prev_p})
      for (std::size_t k = 0; k < 3; ++k)
        (*c)[k].assign(n, f);
    shadow_tmax.assign(n, f);
    for (auto* c : {&next_path, &shadow_path, &shadow_light, &next_depth})
      c->assign(n, kCanary);
    for (auto* c3 : {&shadow_c, &next_beta})
      for (auto& c : *c3)
        c.assign(n, d);
    next_prev_pdf.assign(n, d);
    q.path = path, q.depth = depth;
    for (std::size_t k = 0; k < 3; ++k) {
      q.next_o[k] = next_o[k].data(), q.next_d[k] = next_d[k].data();
      q.shadow_o[k] = shadow_o[k].data(), q.shadow_d[k] = shadow_d[k].data();
      q.shadow_c[k] = shadow_c[k].data(), q.next_beta[k] = next_beta[k].data();
      q.next_prev_p[k] = next_prev_p[k].data();
    }
    q.next_path = next_path.data(), q.shadow_path = shadow_path.data();
    q.shadow_light = shadow_light.data(), q.shadow_tmax = shadow_tmax.data();
    q.next_prev_pdf = next_prev_pdf.data(), q.next_depth = next_depth.data();
  }
  // Whether every value at or past `room` is still its canary.
  bool canaries_alive() const {
    bool alive = true;
    for (std::size_t r = room; r < next_path.size(); ++r) {
      for (const auto* c : {&next_o, &next_d, &shadow_o, &shadow_d, &next_prev_p})
        for (std::size_t k = 0; k < 3; ++k)
          alive = alive && std::bit_cast<uint32_t>((*c)[k][r]) == kCanary;
      for (std::size_t k = 0; k < 3; ++k)
        alive = alive && std::bit_cast<uint64_t>(shadow_c[k][r]) == uint64_t(kCanary) &&
                std::bit_cast<uint64_t>(next_beta[k][r]) == uint64_t(kCanary);
      alive = alive && std::bit_cast<uint32_t>(shadow_tmax[r]) == kCanary &&
              next_path[r] == kCanary && shadow_path[r] == kCanary && shadow_light[r] == kCanary &&
              next_depth[r] == kCanary &&
              std::bit_cast<uint64_t>(next_prev_pdf[r]) == uint64_t(kCanary);
    }
    return alive;
  }
};

// The kernel's queues are finish_vertices' columns (after shade_lanes) filtered by its flags, in
// row order, bit for bit (an origin or end that is NaN in both may differ in its sign:
// same_or_nan); a next ray carries the new throughput and the BSDF's density widened, the
// vertex's point and the depth after the row's.
void expect_queues_are_the_flagged_rows(const Batches& apart, const std::vector<uint32_t>& path,
                                        const std::vector<uint32_t>& depth, std::size_t n,
                                        bool lights, const Queues& got) {
  const VertexBatch& y = apart.vertex;
  std::size_t next = 0, shadows = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (lights && y.shadow_ok[i] != 0) {
      const std::size_t m = shadows++;
      ASSERT_TRUE(m < got.q.shadow_count && same_bits(row(got.shadow_c, m), row(y.shadow_c, i)) &&
                  same_origin(row(got.shadow_o, m), row(y.shadow_o, i)) &&
                  same_bits(row(got.shadow_d, m), row(apart.bsdf.light_wi, i)) &&
                  same_or_nan(got.shadow_tmax[m], y.shadow_tmax[i]) &&
                  got.shadow_light[m] == apart.lights.light[i].bits() &&
                  got.shadow_path[m] == path[i])
          << "shadow ray of row " << i;
    }
    if (y.alive[i] != 0) {
      const std::size_t m = next++;
      ASSERT_TRUE(m < got.q.next_count && same_origin(row(got.next_o, m), row(y.next_o, i)) &&
                  same_bits(row(got.next_d, m), row(apart.bsdf.wi, i)) &&
                  got.next_path[m] == path[i])
          << "next ray of row " << i;
      ASSERT_TRUE(same_bits(row(got.next_beta, m), glm::dvec3(row(y.next_beta, i))) &&
                  same_bits(row(got.next_prev_p, m), row(y.p, i)) &&
                  same_bits(got.next_prev_pdf[m], double(apart.bsdf.pdf[i])) &&
                  got.next_depth[m] == depth[i] + 1)
          << "what the next ray of row " << i << " carries";
    }
  }
  EXPECT_EQ(got.q.shadow_count, shadows);
  EXPECT_EQ(got.q.next_count, next);
  EXPECT_TRUE(got.canaries_alive()) << "a destination written at or past its room";
}

// scatter_vertices is shade_lanes then finish_vertices, then a filter of their rows by their
// flags into the queues, bit for bit: the same BSDF answers, kept in registers instead of
// columns, and the rays packed as they are made. At every instruction set, for row counts from
// 0 to 40 (whole lane batches and partial last ones, whose padding lanes must queue nothing) and
// 5003, with and without lights; nothing written at or past the rows rounded up to 16.
TEST(VertexLanes, ScatterQueuesTheRaysOfTheBsdfAndTheStepsAfterIt) {
  std::vector<Material> materials(3);
  materials[0].kd = {0.5f, 0.4f, 0.3f};
  materials[1].kd = {0.2f, 0.2f, 0.2f}, materials[1].ks = {0.5f, 0.5f, 0.5f},
  materials[1].alpha = 40;
  materials[2].ks = {0.1f, 0.1f, 0.1f}, materials[2].kt = {0.9f, 0.9f, 0.9f},
  materials[2].alpha = 200, materials[2].ior = 1.5f;
  const LaneMaterials lanes(materials);
  Rng rng(23);
  std::vector<std::size_t> sizes;
  for (std::size_t n = 0; n <= 40; ++n)
    sizes.push_back(n);
  sizes.push_back(5003);
  for (Isa isa : supported_isas())
    for (std::size_t n : sizes)
      for (bool lights : {true, false}) {
        SCOPED_TRACE(cat(isa_name(isa), " rows ", n, " lights ", lights));
        const std::size_t padded = (n + 15) / 16 * 16;
        const VertexRules rules{true, true, 0.8};
        Batches b = random_rows(rng, n, rules);
        ShadeBatch& sb = b.bsdf;
        std::vector<uint32_t> path(padded), depth(padded);
        for (std::size_t i = 0; i < n; ++i) {
          const Vec nv = random_unit(rng);
          for (std::size_t k = 0; k < 3; ++k)
            sb.n[k][i] = nv[k];
          sb.material[i] = int32_t(i % 3);
          sb.u_lobe[i] = float(rng.uniform()), sb.u1[i] = float(rng.uniform());
          sb.u2[i] = float(rng.uniform());
          b.lights.light[i] = PrimRef::from_bits(uint32_t(rng.uniform() * 4e9));
          path[i] = uint32_t(rng.uniform() * 4e9), depth[i] = uint32_t(rng.uniform() * 70);
        }
        const LightQueries* with = lights ? &b.lights : nullptr;
        Batches apart = b;
        shade_lanes(isa, lanes, apart.bsdf);
        finish_vertices(isa, rules, apart.bsdf, with, apart.vertex);
        Queues got(padded, 20, path.data(), depth.data());
        scatter_vertices(isa, lanes, rules, b.bsdf, with, b.vertex, got.q);
        expect_queues_are_the_flagged_rows(apart, path, depth, n, lights, got);
        if (n == 5003) {
          EXPECT_GT(got.q.next_count, 1000u);
          if (lights) {
            EXPECT_GT(got.q.shadow_count, 1000u);
          }
        }
        if (!lights) {
          EXPECT_EQ(got.q.shadow_count, 0u);
        }
      }
}

// Whether two runs' queues hold the same bytes, canaries included.
bool same_queues(const Queues& a, const Queues& b) {
  auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0;
  };
  bool ok = a.q.next_count == b.q.next_count && a.q.shadow_count == b.q.shadow_count;
  for (std::size_t k = 0; k < 3; ++k)
    ok = ok && same(a.next_o[k], b.next_o[k]) && same(a.next_d[k], b.next_d[k]) &&
         same(a.shadow_o[k], b.shadow_o[k]) && same(a.shadow_d[k], b.shadow_d[k]) &&
         same(a.next_prev_p[k], b.next_prev_p[k]) && same(a.shadow_c[k], b.shadow_c[k]) &&
         same(a.next_beta[k], b.next_beta[k]);
  return ok && same(a.shadow_tmax, b.shadow_tmax) && same(a.next_path, b.next_path) &&
         same(a.shadow_path, b.shadow_path) && same(a.shadow_light, b.shadow_light) &&
         same(a.next_depth, b.next_depth) && same(a.next_prev_pdf, b.next_prev_pdf);
}

// A scene's one light as broadcast lanes (LightQueries::one_light) is its light and radiance
// in every row's columns: the same queues, byte for byte, at every instruction set, with the
// columns the broadcast leaves unread holding NaN and other lights.
TEST(VertexLanes, ScatterTakesOneLightAsColumnsFilledWithIt) {
  std::vector<Material> materials(2);
  materials[0].kd = {0.5f, 0.4f, 0.3f};
  materials[1].kd = {0.2f, 0.2f, 0.2f}, materials[1].ks = {0.5f, 0.5f, 0.5f},
  materials[1].alpha = 40;
  const LaneMaterials lanes(materials);
  const LightQueries::OneLight one{PrimRef::from_bits(0x12345u), {2.5f, 1.5f, 0.75f}};
  Rng rng(29);
  for (Isa isa : supported_isas())
    for (std::size_t n : {std::size_t(37), std::size_t(5003)}) {
      SCOPED_TRACE(cat(isa_name(isa), " rows ", n));
      const std::size_t padded = (n + 15) / 16 * 16;
      const VertexRules rules{true, true, 0.8};
      Batches columns = random_rows(rng, n, rules);
      std::vector<uint32_t> path(padded), depth(padded);
      for (std::size_t i = 0; i < n; ++i) {
        const Vec nv = random_unit(rng);
        for (std::size_t k = 0; k < 3; ++k)
          columns.bsdf.n[k][i] = nv[k];
        columns.bsdf.material[i] = int32_t(i % 2);
        columns.bsdf.u_lobe[i] = float(rng.uniform()), columns.bsdf.u1[i] = float(rng.uniform());
        columns.bsdf.u2[i] = float(rng.uniform());
        path[i] = uint32_t(i), depth[i] = uint32_t(i % 7);
      }
      Batches broadcast = columns;
      for (std::size_t i = 0; i < padded; ++i) {
        columns.lights.light[i] = one.light;
        broadcast.lights.light[i] = PrimRef::from_bits(uint32_t(i));
        for (std::size_t k = 0; k < 3; ++k) {
          columns.lights.le[k][i] = one.le[k];
          broadcast.lights.le[k][i] = std::numeric_limits<float>::quiet_NaN();
        }
      }
      broadcast.lights.one_light = one;
      Queues from_columns(padded, 20, path.data(), depth.data());
      Queues from_broadcast(padded, 20, path.data(), depth.data());
      scatter_vertices(isa, lanes, rules, columns.bsdf, &columns.lights, columns.vertex,
                       from_columns.q);
      scatter_vertices(isa, lanes, rules, broadcast.bsdf, &broadcast.lights, broadcast.vertex,
                       from_broadcast.q);
      EXPECT_GT(from_columns.q.shadow_count, n / 4);
      EXPECT_TRUE(same_queues(from_columns, from_broadcast));
    }
}

}  // namespace
}  // namespace raylane
