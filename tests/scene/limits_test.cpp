// Sizes that come from input (docs/scene-language.md, "Limits"): big files parse completely and
// correctly, and every size is checked before anything is allocated for it.
#include <gtest/gtest.h>

#include <string>

#include "raylane/core/strings.h"
#include "scene/scene_test_util.h"

namespace raylane {
namespace {

using testing::errors;
using testing::parse;

// A million lines parse completely: every row lands, in order. (How fast is in the
// README's note, not asserted: no timed unit tests.)
TEST(Limits, MillionLineScene) {
  constexpr int kLines = 1000000;
  std::string text = testing::kCameraLine;
  text.reserve(std::size_t(kLines) * 24);
  for (int i = 0; i < kLines; ++i) {
    if (i % 1000 == 0) text += "brdf 0.5 0.5 0.5 0 0 0 1  # a material now and then\r\n";
    text += cat("sphere ", i % 977, " ", i / 977, " 0 0.25\n");
  }
  auto p = parse(text);
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  const auto& t = p.scene.table<Sphere>();
  ASSERT_EQ(t.size(), std::size_t(kLines));
  EXPECT_EQ(p.scene.materials.size(), std::size_t(kLines / 1000));
  EXPECT_EQ(t.material[kLines - 1], uint32_t(kLines / 1000 - 1));
}

// A hundred thousand bad lines are all counted, and only the first Diagnostics::kMaxKept
// are kept with their text, in order: memory does not grow with the number of errors.
TEST(Limits, ManyBadLinesAreCountedNotAllKept) {
  constexpr int kBad = 100000;
  std::string text = testing::kCameraLine;
  for (int i = 0; i < kBad; ++i)
    text += "sphere 0 0 zero 1\n";
  auto p = parse(text);
  EXPECT_EQ(p.diagnostics.error_count(), kBad);
  EXPECT_EQ(p.diagnostics.warning_count(), 1);  // no screen line, said after the last line
  EXPECT_EQ(p.diagnostics.items.size(), Diagnostics::kMaxKept);
  EXPECT_EQ(p.diagnostics.dropped(), kBad + 1 - int(Diagnostics::kMaxKept));
  EXPECT_EQ(to_string(p.diagnostics.items.front().loc), "t.scn:2:12");
  EXPECT_EQ(to_string(p.diagnostics.items.back().loc),
            cat("t.scn:", Diagnostics::kMaxKept + 1, ":12"));
}

// The orientation list is bounded by the line length only; a long one is still exact
// rotation algebra: 10^4 turns of 36° about x is 1000 full turns.
TEST(Limits, LongOrientationList) {
  std::string line = "camera 0 0 5 0.5";
  for (int i = 0; i < 10000; ++i)
    line += " x 36";
  auto p = parse(line + "\n");
  ASSERT_TRUE(p.ok()) << errors(p)[0];
  const glm::dmat3& r = p.scene.camera->rotation;
  glm::dvec3 y = r * glm::dvec3(0, 1, 0);
  EXPECT_NEAR(y.x, 0, 1e-9);
  EXPECT_NEAR(y.y, 1, 1e-9);
  EXPECT_NEAR(y.z, 0, 1e-9);
}

// Sizes past a limit are errors with a location, before any allocation: a screen of 2^32
// pixels per side, a line over the limit, a line with a NUL and a very long word.
TEST(Limits, OversizedInputsAreErrors) {
  auto p = parse(std::string(testing::kCameraLine) + "screen 4294967296 1\n");
  ASSERT_EQ(errors(p).size(), 1u);
  EXPECT_EQ(errors(p)[0],
            "t.scn:2:8: screen side 4294967296 is more than 2^28 (268435456), the pixel limit");
  std::string word(kMaxLineBytes - 100, 'a');
  p = parse(std::string(testing::kCameraLine) + "sphere " + word + " 0 0 1\n");
  ASSERT_EQ(errors(p).size(), 1u);
  EXPECT_NE(errors(p)[0].find("t.scn:2:8: "), std::string::npos) << errors(p)[0];
  p = parse(std::string(testing::kCameraLine) + std::string("sphere 0 0\0 0 1\n", 16));
  EXPECT_EQ(errors(p).size(), 1u);
}

}  // namespace
}  // namespace raylane
