#include "raylane/core/alloc_budget.h"

#include <malloc.h>

#include <cstdlib>
#include <new>

// The sanitizers' runtimes define operator new and delete themselves; replacing them there
// would clash at link time, so those builds count nothing and enforce nothing.
#if defined(__SANITIZE_ADDRESS__)
#define RAYLANE_OWN_OPERATOR_NEW 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
#define RAYLANE_OWN_OPERATOR_NEW 0
#endif
#endif
#ifndef RAYLANE_OWN_OPERATOR_NEW
#define RAYLANE_OWN_OPERATOR_NEW 1
#endif

namespace raylane {

namespace {
thread_local AllocBudget* t_budget = nullptr;
}

AllocBudget::AllocBudget(uint64_t limit_bytes) : outer_(t_budget), limit_(limit_bytes) {
  t_budget = this;
}

AllocBudget::~AllocBudget() {
  t_budget = outer_;
}

bool AllocBudget::enforced() {
  return RAYLANE_OWN_OPERATOR_NEW != 0;
}

bool AllocBudget::take(uint64_t bytes) {
  if (live_ + bytes > limit_) {
    exceeded_ = true;
    return false;
  }
  live_ += bytes;
  if (live_ > peak_) peak_ = live_;
  return true;
}

void AllocBudget::give(uint64_t bytes) {
  live_ = bytes > live_ ? 0 : live_ - bytes;  // memory from before the budget may be freed
}

}  // namespace raylane

#if RAYLANE_OWN_OPERATOR_NEW
namespace {

void* allocate(std::size_t n) {
  void* p = std::malloc(n ? n : 1);
  if (!p) return nullptr;
  if (raylane::t_budget && !raylane::t_budget->take(malloc_usable_size(p))) {
    std::free(p);
    return nullptr;
  }
  return p;
}

void release(void* p) noexcept {
  if (p && raylane::t_budget) raylane::t_budget->give(malloc_usable_size(p));
  std::free(p);
}

}  // namespace

void* operator new(std::size_t n) {
  if (void* p = allocate(n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  if (void* p = allocate(n)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  return allocate(n);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  return allocate(n);
}
void operator delete(void* p) noexcept {
  release(p);
}
void operator delete[](void* p) noexcept {
  release(p);
}
void operator delete(void* p, std::size_t) noexcept {
  release(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  release(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  release(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  release(p);
}
#endif
