// Limits on what any input may announce, checked before anything is allocated; shared by the
// scene parser, the image readers and the film.
#pragma once

#include <cstdint>

namespace raylane {

// The largest image: a `screen` line, an image file or a film of at most 2^28 pixels.
inline constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;

}  // namespace raylane
