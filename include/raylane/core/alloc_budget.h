// A cap on what one piece of work may allocate, for code that is not ours: mesh importers
// size their arrays from counts a file announces, and a 230-byte file that announces 10^8
// vertices would have them allocate gigabytes before reading a byte of them. While an
// AllocBudget is alive, every operator new on its thread counts against it, and one that
// would take the bytes live since it started past its limit throws std::bad_alloc (which the
// importer turns into an error naming the file). raylane replaces the global operator new
// and delete for this (src/core/alloc_budget.cpp); the sanitizer builds keep their own, and
// there the budget only counts (enforced() says which).
#pragma once

#include <cstdint>

namespace raylane {

class AllocBudget {
 public:
  explicit AllocBudget(uint64_t limit_bytes);
  ~AllocBudget();
  AllocBudget(const AllocBudget&) = delete;
  AllocBudget& operator=(const AllocBudget&) = delete;

  void grow(uint64_t bytes) { limit_ += bytes; }  // e.g. for each further file read
  uint64_t limit() const { return limit_; }
  uint64_t peak() const { return peak_; }  // the most bytes live at once, so far
  bool exceeded() const { return exceeded_; }
  static bool enforced();  // false where the sanitizers own operator new

  // Called by operator new and delete of this thread (bytes as malloc_usable_size reports).
  bool take(uint64_t bytes);
  void give(uint64_t bytes);

 private:
  AllocBudget* outer_;  // budgets nest: the inner one counts, the outer one resumes after
  uint64_t limit_, live_ = 0, peak_ = 0;
  bool exceeded_ = false;
};

}  // namespace raylane
