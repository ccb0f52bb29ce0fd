// What `csg` and `sdf` blocks (docs/scene-language.md, "CSG blocks", "SDF blocks") read alike:
// where a block was opened, counts of solids, operator and `end` lines without parameters,
// and the material a leaf takes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "raylane/scene/parse_state.h"
#include "raylane/scene/scene.h"

namespace raylane {

// "line 4" for a block opened in the line's own file, else its full location.
std::string opened_at(const FileLoc& at, const Line& line);

// "1 solid", "2 solids".
std::string solids(uint32_t n);

// True when the line is its word alone; else a problem at its first parameter.
bool no_parameters(const Line& line, ParseState& state);

// The material a leaf of `block` ("a csg", "an sdf") takes: the current one, which must not emit (a
// light's area could not be sampled on a solid whose surface is only known along rays); the
// default grey one, with a warning, before any material line (as for any shape).
std::optional<uint32_t> leaf_material(Scene& s, const Line& line, ParseState& state,
                                      std::string_view block);

}  // namespace raylane
