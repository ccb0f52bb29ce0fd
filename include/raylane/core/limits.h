// Limits on what any input may announce, checked before anything is allocated; shared by the
// scene parser, the image readers and the film.
#pragma once

#include <cstdint>

namespace raylane {

// The largest image: a `screen` line, an image file or a film of at most 2^28 pixels.
inline constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;

// What decoding the images one command reads (a scene's textures and environment, the images
// `convert` and `diff` read) may take in all, by default: decoded pixels and the decoders'
// working memory, counted from each header before anything is decoded, so that a file of a
// few kilobytes that decodes to gigabytes (a decompression bomb) is refused however it is
// compressed. `--image-memory MIB` raises it; this default keeps a command that reads hostile
// images under 256 MiB.
inline constexpr uint64_t kDefaultImageMemory = uint64_t(192) << 20;

}  // namespace raylane
