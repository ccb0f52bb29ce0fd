// Scalar 3-vectors are GLM's: glm::vec3 (float: hot code, tables) and glm::dvec3 (double: the
// reference kernels, which convert float inputs exactly, docs/hard-cases.md §0), generically
// glm::vec<3, T>. This header adds the few operations GLM lacks or rounds differently.
//
// GLM is configured once, by compile definitions on raylane_lib (CMakeLists.txt), never by a
// #define before an include (one forgotten include order would silently change every type):
//   GLM_FORCE_EXPLICIT_CTOR  float <-> double conversions between vectors are written out;
//   GLM_FORCE_PURE           no GLM intrinsics: scalar code that rounds as written (the SIMD
//                            lanes are xsimd's, simd/lanes.h);
//   GLM_FORCE_XYZW_ONLY      plain x, y, z members (no r/g/b unions, no swizzles).
// Not GLM_FORCE_CTOR_INIT: in GLM 0.9.9 it also replaces the defaulted copy constructor and
// assignment by hand-written ones, so glm::vec3 stops being trivially copyable (passed and
// returned through memory by the x86-64 ABI, copied element by element). So a
// default-constructed GLM vector is uninitialised, as a float is: raylane writes `v{}` (zero),
// a matrix `m{1.0}` (identity), a quaternion `q{1, 0, 0, 0}` wherever it declares one without
// a value.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#if !defined(GLM_FORCE_EXPLICIT_CTOR) || !defined(GLM_FORCE_PURE) || \
    !defined(GLM_FORCE_XYZW_ONLY) || defined(GLM_FORCE_CTOR_INIT)
#error "GLM must be configured by raylane_lib's compile definitions (link the target)"
#endif

namespace raylane {

// glm::dot is (x·x' + y·y') + z·z' and glm::cross the same three differences of products as the
// kernels' error bounds assume (docs/hard-cases.md; the build has -ffp-contract=off), and
// glm::length is sqrt(dot): those are used as they are.

// a / |a|, one division per component. glm::normalize is a·inversesqrt(a·a), whose last bit can
// differ; the references and the bounds of docs/hard-cases.md assume this order, so every
// unqualified normalize() of a glm::vec<3, T> resolves here (more specialised than GLM's
// template). Contract: |a| > 0; a zero vector gives NaN components (callers check first).
template <class T>
glm::vec<3, T> normalize(const glm::vec<3, T>& a) {
  return a / glm::length(a);
}
template <class T>
constexpr T length_squared(const glm::vec<3, T>& a) {
  return glm::dot(a, a);
}
// Component-wise min and max in std::min/std::max's order (the same as glm::min/glm::max).
template <class T>
constexpr glm::vec<3, T> min(const glm::vec<3, T>& a, const glm::vec<3, T>& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
template <class T>
constexpr glm::vec<3, T> max(const glm::vec<3, T>& a, const glm::vec<3, T>& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
// std::abs clears the sign bit; glm::abs is x >= 0 ? x : −x, which keeps −0 and flips a NaN's sign.
template <class T>
glm::vec<3, T> abs(const glm::vec<3, T>& a) {
  return {std::abs(a.x), std::abs(a.y), std::abs(a.z)};
}
template <class T>
constexpr T max_component(const glm::vec<3, T>& a) {
  return std::max(a.x, std::max(a.y, a.z));
}
// Index of the largest component; ties go to the lowest axis.
template <class T>
constexpr int max_dimension(const glm::vec<3, T>& a) {
  return (a.x >= a.y) ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
}
template <class T>
constexpr glm::vec<3, T> permute(const glm::vec<3, T>& a, int i, int j, int k) {
  return {a[i], a[j], a[k]};
}
template <class T>
bool is_finite(const glm::vec<3, T>& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

}  // namespace raylane
