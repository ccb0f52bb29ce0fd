// The orientation mini-language: `x A`, `y A`, `z A`, `a A ax ay az`, `q w x y z`, composed
// left to right by multiplying each new rotation on the right (docs/scene-language.md).
#pragma once

#include <cstddef>
#include <optional>

#include "raylane/core/rotation.h"
#include "raylane/scene/parse_state.h"
#include "raylane/scene/scene.h"

namespace raylane {

// Parses tokens [first, end of line) of `line`; an empty list is the identity.
std::optional<glm::dmat3> parse_orientation(const Line& line, std::size_t first, ParseState& state);

}  // namespace raylane
