// Limits on what any input may announce, checked before anything is allocated; shared by the
// scene parser, the image readers and the film.
#pragma once

#include <cstdint>

namespace raylane {

// The largest image: a `screen` line, an image file or a film of at most 2^28 pixels.
inline constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;

// What decoding the images one command reads (a scene's textures and environment, the images
// `convert` and `diff` read) may take in all is its image memory: decoded texels, the decoders'
// working memory and the environment's sampling tables, counted from each header before
// anything is decoded. By default it is half of what this process can have (core/memory.h,
// default_image_memory), and never less than this floor; `--image-memory MIB` sets it.
inline constexpr uint64_t kDefaultImageMemory = uint64_t(192) << 20;

// The decompression-bomb rule, at the default image memory only (docs/scene-language.md, "Image
// memory"): an image whose decoding takes more than kBombFloorBytes and more than
// kMaxDecodeRatio times its file's bytes is refused unless the user sets --image-memory, as
// image libraries' safety limits refuse what a small file should not become (Pillow's
// MAX_IMAGE_PIXELS, libpng's user limits). Real images stay far below the ratio: an 8-bit
// photograph's PNG or JPEG decodes to 5 to 100 times its size, an HDR sky's to 3 to 10, while
// deflate alone reaches 1032:1 and a bomb's decoding 10^4 times its file.
inline constexpr uint64_t kBombFloorBytes = uint64_t(256) << 20;
inline constexpr uint64_t kMaxDecodeRatio = 1024;

}  // namespace raylane
