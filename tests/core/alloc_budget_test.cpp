// The allocation budget that bounds what code not ours (mesh importers) may allocate.
#include <gtest/gtest.h>

#include <memory>
#include <new>
#include <vector>

#include "raylane/core/alloc_budget.h"

namespace raylane {
namespace {

char* volatile sink = nullptr;

TEST(AllocBudget, RefusesWhatWouldPassItsLimitAndCountsWhatItAllows) {
  if (!AllocBudget::enforced()) GTEST_SKIP() << "the sanitizer build keeps its own operator new";
  AllocBudget budget(1 << 20);
  auto small = std::make_unique<char[]>(1000);  // within the limit
  EXPECT_THROW((void)std::make_unique<char[]>(2 << 20), std::bad_alloc);
  EXPECT_TRUE(budget.exceeded());
  EXPECT_GE(budget.peak(), 1000u);
  EXPECT_LT(budget.peak(), uint64_t(1) << 20);
  // Freed bytes come back: many allocations that are each freed stay within the limit.
  AllocBudget inner(1 << 16);
  for (int i = 0; i < 1000; ++i) {
    std::vector<char> v(1 << 15);
    sink = v.data();  // kept observable, so the allocation is not elided
  }
  EXPECT_FALSE(inner.exceeded());
}

TEST(AllocBudget, EndsWithItsScope) {
  if (!AllocBudget::enforced()) GTEST_SKIP() << "the sanitizer build keeps its own operator new";
  { AllocBudget budget(16); }
  EXPECT_NO_THROW((void)std::make_unique<char[]>(1 << 20));
}

}  // namespace
}  // namespace raylane
