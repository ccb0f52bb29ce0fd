// Bit-for-bit equality of doubles, floats and vectors: lane code that computes the scalar code's
// operations in its order (the build compiles with -ffp-contract=off, so no multiply and add
// fuse on either side) must give the scalar results exactly, at every instruction set.
#pragma once

#include <bit>
#include <cstdint>

#include "raylane/core/vec_math.h"

namespace raylane::testing {

inline bool same_bits(double a, double b) {
  return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b);
}
inline bool same_bits(const glm::dvec3& a, const glm::dvec3& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}
inline bool same_bits(float a, float b) {
  return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}
inline bool same_bits(const glm::vec3& a, const glm::vec3& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

}  // namespace raylane::testing
