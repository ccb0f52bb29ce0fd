// The tiles of an image shared between processes (render/film/tile_share.h, docs/cluster.md): the
// film's pixels map to the render's tiles; films of disjoint shares OR together into the
// single-process film bit for bit, also when the tiles change hands between passes; the
// largest-cost-first deal meets its bound where round-robin does not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <random>

#include "raylane/render/film/film.h"
#include "raylane/render/film/tile_share.h"
#include "raylane/scene/parser.h"
#include "support/paths.h"

namespace raylane {
namespace {

struct Loaded {
  Scene scene;
  Bvh bvh;
};

// sphere.scn is 160x120: 120 rows are 7.5 tiles, so a film row and a render row fall in tiles
// numbered from opposite ends.
Loaded load_sphere() {
  auto p = load_scene_file(testing::source_path("scenes/sphere.scn"));
  EXPECT_TRUE(p.ok());
  Loaded r{std::move(p.scene), {}};
  r.bvh = build_bvh_and_reorder(r.scene);
  return r;
}

PathSettings settings(int spp, TileShare share = {}) {
  PathSettings s;
  s.spp = spp;
  s.seed = 11;
  s.share = std::move(share);
  return s;
}

// What the cluster's reduction does: a bitwise OR of the doubles' bits.
void or_into(std::vector<double>& into, const std::vector<double>& from) {
  ASSERT_EQ(into.size(), from.size());
  for (std::size_t i = 0; i < into.size(); ++i) {
    uint64_t a, b;
    std::memcpy(&a, &into[i], 8);
    std::memcpy(&b, &from[i], 8);
    a |= b;
    std::memcpy(&into[i], &a, 8);
  }
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * 8) == 0;
}

TEST(TileShare, AFilmKeepsExactlyItsShareOfTheRender) {
  Loaded r = load_sphere();
  Tracer tracer(r.scene, r.bvh, TracerBackend::kPacket);
  Film whole;
  render_path(tracer, settings(2), nullptr, &whole);
  for (uint32_t index = 0; index < 3; ++index) {
    TileShare share{index, 3, nullptr};
    Film mine;
    render_path(tracer, settings(2, share), nullptr, &mine);
    Film kept = whole;
    keep_share(kept, share);
    EXPECT_TRUE(same_bits(kept.sum, mine.sum)) << "process " << index;
    EXPECT_TRUE(std::any_of(mine.sum.begin(), mine.sum.end(), [](double v) { return v > 0; }));
  }
}

TEST(TileShare, TilesChangingHandsBetweenPassesKeepTheImage) {
  Loaded r = load_sphere();
  Tracer tracer(r.scene, r.bvh, TracerBackend::kPacket);
  Film whole;
  render_path(tracer, settings(5), nullptr, &whole);

  // Two processes, round-robin for 2 passes; then the tiles are dealt by a table (each
  // process takes the whole film and keeps its new tiles); then 3 more passes.
  Film film[2];
  for (uint32_t p = 0; p < 2; ++p)
    render_path(tracer, settings(2, {p, 2, nullptr}), nullptr, &film[p]);
  std::vector<double> cost(((160 + 15) / 16) * ((120 + 15) / 16));  // sphere.scn's tiles
  std::mt19937 rng(5);
  for (double& c : cost)
    c = std::uniform_real_distribution<double>(0.1, 3)(rng);
  auto table = std::make_shared<const std::vector<uint32_t>>(balance_tiles(cost, 2));
  Film both = film[0];
  or_into(both.sum, film[1].sum);
  for (uint32_t p = 0; p < 2; ++p) {
    film[p] = both;
    keep_share(film[p], {p, 2, table});
    render_path(tracer, settings(5, {p, 2, table}), nullptr, &film[p]);
  }
  or_into(film[0].sum, film[1].sum);
  EXPECT_TRUE(same_bits(film[0].sum, whole.sum));
}

TEST(TileShare, ReshareIsCalledBetweenPassesWithTheTilesCosts) {
  Loaded r = load_sphere();
  Tracer tracer(r.scene, r.bvh, TracerBackend::kPacket);
  Film one_pass;
  render_path(tracer, settings(1), nullptr, &one_pass);

  PathSettings s = settings(3, {0, 2, nullptr});
  int calls = 0;
  s.reshare = [&](const std::vector<double>& seconds) {
    ++calls;
    // Timed: its own tiles of the pass just taken, and none after it gave them all away.
    for (std::size_t t = 0; t < seconds.size(); ++t)
      EXPECT_EQ(seconds[t] > 0, calls == 1 && t % 2 == 0) << "tile " << t << ", pass " << calls;
    // After the first pass every tile goes to the other process: this one renders no more.
    auto none = std::make_shared<const std::vector<uint32_t>>(seconds.size(), 1u);
    return TileShare{0, 2, none};
  };
  Film film;
  render_path(tracer, s, nullptr, &film);
  EXPECT_EQ(calls, 2);  // after passes 1 and 2, not after the last
  EXPECT_EQ(film.passes, 3);
  Film kept = one_pass;
  keep_share(kept, {0, 2, nullptr});
  EXPECT_TRUE(same_bits(film.sum, kept.sum));  // pass 1 of its own tiles, nothing after
}

TEST(TileShare, LargestFirstMeetsGrahamsBoundWhereRoundRobinDoesNot) {
  // Costs with the period of the process count: round-robin gives one process every dear tile.
  const uint32_t processes = 4;
  std::vector<double> cost(400);
  for (std::size_t t = 0; t < cost.size(); ++t)
    cost[t] = t % processes == 0 ? 10 : 1;
  double max_cost = 10, mean = 0;
  for (double c : cost)
    mean += c / processes;
  double round_robin = imbalance(process_loads(cost, {0, processes, nullptr}));
  EXPECT_GT(round_robin, 2.0);
  auto table = std::make_shared<const std::vector<uint32_t>>(balance_tiles(cost, processes));
  std::vector<double> loads = process_loads(cost, {0, processes, table});
  EXPECT_LE(*std::max_element(loads.begin(), loads.end()), mean + max_cost);
  EXPECT_LT(imbalance(loads), 1.01);

  // Random costs: every tile has a process, the bound holds, the same costs deal the same.
  std::mt19937 rng(9);
  for (int round = 0; round < 20; ++round) {
    std::vector<double> c(1 + rng() % 3000);
    for (double& v : c)
      v = std::exponential_distribution<double>(1.0)(rng);
    uint32_t n = 1 + rng() % 64;
    std::vector<uint32_t> dealt = balance_tiles(c, n);
    ASSERT_EQ(dealt.size(), c.size());
    EXPECT_TRUE(std::all_of(dealt.begin(), dealt.end(), [&](uint32_t p) { return p < n; }));
    auto shared = std::make_shared<const std::vector<uint32_t>>(dealt);
    std::vector<double> l = process_loads(c, {0, n, shared});
    double total = 0;
    for (double v : c)
      total += v;
    double most = *std::max_element(c.begin(), c.end());
    EXPECT_LE(*std::max_element(l.begin(), l.end()), total / n + most + 1e-9 * total);
    EXPECT_EQ(balance_tiles(c, n), dealt);
  }
}

TEST(TileShare, ImbalanceIsTheHeaviestOverTheMean) {
  EXPECT_DOUBLE_EQ(imbalance({1, 1, 1, 1}), 1.0);
  EXPECT_DOUBLE_EQ(imbalance({2, 1, 1, 0}), 2.0);
  EXPECT_DOUBLE_EQ(imbalance({0, 0}), 1.0);  // nothing measured: nothing to even out
  EXPECT_EQ(process_loads({1, 2, 3, 4, 5}, {0, 2, nullptr}), (std::vector<double>{9, 6}));
}

}  // namespace
}  // namespace raylane
