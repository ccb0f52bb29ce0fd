// Arbitrary output variables of the path render (`--aov`): what the first surface each camera
// sample meets looks like, accumulated at the same samples as the colour and averaged over the
// pixel's samples, so they line up with the antialiased image (what denoisers take beside it).
// A sample that meets nothing adds zeros. Conventions (docs/scene-language.md, "Output"):
// albedo is Kd times the texture (as `--mode albedo`), the normal is the unit shading normal in
// world space (outward, not turned toward the camera; an average of unit normals is shorter
// than 1 at edges), depth is the hit's ray parameter t, position the world-space hit point.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "raylane/core/enum_names.h"
#include "raylane/core/error.h"

namespace raylane {

enum class Aov : uint8_t { kAlbedo, kNormal, kDepth, kPosition };
inline constexpr std::size_t kAovCount = 4;
inline constexpr EnumNames<Aov, kAovCount> kAovNames{{"albedo", "normal", "depth", "position"}};

inline constexpr int aov_channels(Aov a) {
  return a == Aov::kDepth ? 1 : 3;
}

// A set of AOVs (bit k: Aov k) and where each one's channels sit in a pixel's AOV sums, in
// Aov order.
struct AovSet {
  uint32_t bits = 0;

  bool has(Aov a) const { return bits >> unsigned(a) & 1u; }
  bool empty() const { return bits == 0; }
  // Channels per pixel of all the set's AOVs.
  int channels() const {
    int n = 0;
    for (std::size_t k = 0; k < kAovCount; ++k)
      if (has(Aov(k))) n += aov_channels(Aov(k));
    return n;
  }
  // The first channel of `a` within a pixel's sums (a must be in the set).
  int offset(Aov a) const {
    int n = 0;
    for (std::size_t k = 0; k < std::size_t(a); ++k)
      if (has(Aov(k))) n += aov_channels(Aov(k));
    return n;
  }
  bool operator==(const AovSet&) const = default;
};

// "albedo,normal" → the set; an unknown or repeated name is an error that lists the choices.
Result<AovSet> parse_aov_list(const std::string& text);
// "albedo, normal": the set's names, for messages.
std::string aov_list_text(AovSet set);

}  // namespace raylane
