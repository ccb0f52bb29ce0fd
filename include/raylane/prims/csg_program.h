// A CSG block's postfix program (docs/scene-language.md, "CSG blocks"): its codes,
// the classification of a point by the program (Roth 1982, "Ray casting for modeling solids",
// CGIP 18(2), §4: a point is in A op B as the set operation says of its being in A and in B),
// and the block's bounds by the same program.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "raylane/core/bounds3.h"

namespace raylane {

// A program code: a leaf's index within its block (below kCsgMaxLeaves) or an operator.
enum CsgCode : uint32_t { kCsgUnion = 0x100, kCsgIntersect = 0x101, kCsgDifference = 0x102 };

// Leaves per block: a point's membership of every leaf is one 64-bit mask, and the kernels'
// per-leaf arrays live on the stack (nothing is allocated per ray). The program of n leaves has
// n − 1 operators, so its stack never holds more than n entries.
inline constexpr uint32_t kCsgMaxLeaves = 64;

inline std::string_view csg_code_name(uint32_t code) {
  switch (code) {
    case kCsgUnion:
      return "union";
    case kCsgIntersect:
      return "intersect";
    case kCsgDifference:
      return "difference";
    default:
      return "leaf";
  }
}

// Whether a point inside exactly the leaves of `inside` (bit i: leaf i) is in the solid. The
// stack of truth values is a bit stack: bit k is the entry k from the bottom. Bits above the
// top are left over from popped entries, so a push clears its bit before setting it.
inline bool csg_classify(std::span<const uint32_t> program, uint64_t inside) {
  uint64_t stack = 0;
  int top = 0;
  auto push = [&](bool v) {
    stack = (stack & ~(uint64_t(1) << top)) | (uint64_t(v) << top);
    ++top;
  };
  for (uint32_t code : program) {
    if (code < kCsgMaxLeaves) {
      push((inside >> code) & 1u);
      continue;
    }
    bool b = (stack >> --top) & 1u, a = (stack >> --top) & 1u;
    push(code == kCsgUnion ? (a || b) : code == kCsgIntersect ? (a && b) : (a && !b));
  }
  return stack & 1u;
}

// The block's bounds for the BVH by the spec's rule: A ∪ B the union of the bounds, A ∩ B their
// intersection (possibly empty), A − B those of A. `leaf_bounds(i)` gives leaf i's.
template <class LeafBounds>
Bounds3f csg_bounds(std::span<const uint32_t> program, const LeafBounds& leaf_bounds) {
  Bounds3f stack[kCsgMaxLeaves];
  int top = 0;
  for (uint32_t code : program) {
    if (code < kCsgMaxLeaves) {
      stack[top++] = leaf_bounds(code);
      continue;
    }
    Bounds3f b = stack[--top], a = stack[--top];
    if (code == kCsgUnion) {
      a.extend(b);
    } else if (code == kCsgIntersect) {
      Bounds3f both;  // assigned, not constructed: the constructor would sort the corners
      both.lo = max(a.lo, b.lo), both.hi = min(a.hi, b.hi);
      a = both.empty() ? Bounds3f() : both;
    }
    stack[top++] = a;
  }
  return stack[0];
}

// Whether each leaf's surface bounds its solid turned inside out: the leaf lies within the B of
// an odd number of differences (A − B = A ∩ ¬B; union and intersection keep orientation). A
// postfix subtree's leaves are consecutive, so each stack entry is a range of leaves.
inline void csg_flips(std::span<const uint32_t> program, std::span<uint8_t> flip) {
  uint32_t first[kCsgMaxLeaves], end[kCsgMaxLeaves];
  int top = 0;
  for (uint32_t code : program) {
    if (code < kCsgMaxLeaves) {
      first[top] = code, end[top] = code + 1, flip[code] = 0;
      ++top;
      continue;
    }
    --top;
    if (code == kCsgDifference)
      for (uint32_t i = first[top]; i < end[top]; ++i)
        flip[i] ^= 1u;
    end[top - 1] = end[top];
  }
}

}  // namespace raylane
