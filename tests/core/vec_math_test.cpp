// GLM as raylane configures it (core/vec_math.h): the properties the code relies on.
#include "raylane/core/vec_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <type_traits>

#include "raylane/core/rotation.h"

namespace raylane {
namespace {

// Passed and returned in registers, copied as bytes: what GLM_FORCE_CTOR_INIT would take away.
TEST(GlmConfiguration, ValuesAreTriviallyCopyableAndBracesZeroThem) {
  static_assert(std::is_trivially_copyable_v<glm::vec3>);
  static_assert(std::is_trivially_copyable_v<glm::dvec3>);
  static_assert(std::is_trivially_copyable_v<glm::dmat3>);
  static_assert(std::is_trivially_copyable_v<glm::dquat>);
  glm::vec3 f{};
  glm::dvec3 d{};
  glm::dmat3 m{1.0};
  glm::dquat q{1, 0, 0, 0};
  EXPECT_EQ(f, glm::vec3(0, 0, 0));
  EXPECT_EQ(d, glm::dvec3(0, 0, 0));
  EXPECT_EQ(m * glm::dvec3(1, 2, 3), glm::dvec3(1, 2, 3));
  EXPECT_EQ(glm::mat3_cast(q), m);
}

TEST(GlmConfiguration, FloatDoubleConversionsAreExplicit) {
  static_assert(!std::is_convertible_v<glm::vec3, glm::dvec3>);
  static_assert(!std::is_convertible_v<glm::dvec3, glm::vec3>);
  static_assert(std::is_constructible_v<glm::dvec3, glm::vec3>);
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));  // no padding, no SIMD alignment
  EXPECT_EQ(glm::dvec3(glm::vec3(0.1f, 0, 0)).x, double(0.1f));
}

// normalize is a / |a| (the order docs/hard-cases.md assumes), not glm::normalize's
// a · inversesqrt(a · a): over random vectors the two differ in some last bit, and the
// unqualified call always gives the division.
TEST(Normalize, DividesByTheLengthNotMultipliesByItsInverse) {
  std::mt19937_64 rng(36);
  std::uniform_real_distribution<double> u(-1, 1);
  int glm_differs = 0;
  for (int i = 0; i < 1000; ++i) {
    glm::dvec3 a(u(rng), u(rng), u(rng));
    double len = glm::length(a);
    glm::dvec3 expected(a.x / len, a.y / len, a.z / len);
    EXPECT_EQ(normalize(a), expected);
    glm::vec3 f(a);
    float lenf = glm::length(f);
    EXPECT_EQ(normalize(f), glm::vec3(f.x / lenf, f.y / lenf, f.z / lenf));
    glm_differs += glm::normalize(a) != expected;
  }
  EXPECT_GT(glm_differs, 0);  // else this test could not tell the two apart
}

TEST(VecMath, AbsClearsTheSignOfZero) {
  glm::vec3 a = abs(glm::vec3(-0.0f, -2.0f, 3.0f));
  EXPECT_FALSE(std::signbit(a.x));
  EXPECT_EQ(a, glm::vec3(0, 2, 3));
}

TEST(VecMath, MaxDimensionBreaksTiesTowardTheLowestAxis) {
  EXPECT_EQ(max_dimension(glm::vec3(1, 1, 1)), 0);
  EXPECT_EQ(max_dimension(glm::vec3(0, 2, 2)), 1);
  EXPECT_EQ(max_dimension(glm::vec3(0, 1, 2)), 2);
  EXPECT_EQ(permute(glm::vec3(1, 2, 3), 2, 0, 1), glm::vec3(3, 1, 2));
}

// glm::dmat3 is column-major: rotation_axis_angle's m[column][row] turns x into y about z.
TEST(Rotation, AxisAngleFollowsTheRightHandRule) {
  glm::dvec3 y = rotation_axis_angle({0, 0, 1}, 90) * glm::dvec3(1, 0, 0);
  EXPECT_NEAR(y.x, 0, 1e-15);
  EXPECT_NEAR(y.y, 1, 1e-15);
  EXPECT_NEAR(y.z, 0, 1e-15);
  glm::dmat3 q = glm::mat3_cast(glm::dquat(std::sqrt(0.5), 0, 0, std::sqrt(0.5)));
  glm::dvec3 yq = q * glm::dvec3(1, 0, 0);
  EXPECT_NEAR(yq.y, 1, 1e-15);
  EXPECT_NEAR(yq.x, 0, 1e-15);
}

}  // namespace
}  // namespace raylane
