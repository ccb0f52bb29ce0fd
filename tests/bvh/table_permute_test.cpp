// table_permute (include/raylane/prims/table_util.h), which the BVH build calls on every table:
// each column, optional ones included, ends up with old row order[i] at row i, whether the
// table is small (the calling thread, each column into the last one's old rows) or large (the
// columns shared out to the threads, each reusing its own old rows), at 1 and 2 threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <tuple>
#include <vector>

#include "raylane/prims/table_util.h"
#include "raylane/prims/triangle.h"

namespace raylane {
namespace {

TriangleTable random_triangles(uint32_t rows, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  TriangleTable t;
  t.add_uv_columns();
  for (uint32_t i = 0; i < rows; ++i) {
    auto v = [&] { return glm::vec3(u(rng), u(rng), u(rng)); };
    std::array<TexCoord, 3> uv{TexCoord{u(rng), u(rng)}, TexCoord{u(rng), u(rng)},
                               TexCoord{u(rng), u(rng)}};
    t.append({v(), v(), v()}, {v(), v(), v()}, i, &uv);
  }
  return t;
}

template <class Col>
void expect_permuted(const Col& before, const Col& after, const std::vector<uint32_t>& order,
                     std::size_t column) {
  ASSERT_EQ(after.size(), order.size()) << "column " << column;
  for (std::size_t i = 0; i < order.size(); ++i)
    ASSERT_EQ(after[i], before[order[i]]) << "column " << column << " row " << i;
}

template <class Tuple, std::size_t... I>
void expect_all(const Tuple& before, const Tuple& after, const std::vector<uint32_t>& order,
                std::size_t first, std::index_sequence<I...>) {
  (expect_permuted(std::get<I>(before), std::get<I>(after), order, first + I), ...);
}

TEST(TablePermute, EveryColumnFollowsTheOrderAtAnySize) {
  std::mt19937 rng(41);
  const int threads_before = omp_get_max_threads();
  for (uint32_t rows : {1u, 100u, 4096u, 4097u, 20000u}) {
    for (int threads : {1, 2}) {
      omp_set_num_threads(threads);
      TriangleTable before = random_triangles(rows, rng), after = before;
      std::vector<uint32_t> order(rows);
      std::iota(order.begin(), order.end(), 0u);
      std::shuffle(order.begin(), order.end(), rng);
      table_permute(after, order);
      constexpr std::size_t kColumns = std::tuple_size_v<decltype(before.columns())>;
      expect_all(before.columns(), after.columns(), order, 0, std::make_index_sequence<kColumns>());
      expect_all(
          before.optional_columns(), after.optional_columns(), order, kColumns,
          std::make_index_sequence<std::tuple_size_v<decltype(before.optional_columns())>>());
    }
  }
  omp_set_num_threads(threads_before);
}

}  // namespace
}  // namespace raylane
