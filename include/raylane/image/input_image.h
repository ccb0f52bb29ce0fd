// Reading textures and environments: PNG, TGA and BMP through stb_image (Debian's libstb-dev),
// JPEG through libjpeg-turbo (stb_image 2.27's JPEG reader has memory errors on damaged files),
// Radiance HDR and PFM through raylane's own readers (image/rgbe.h, image/pfm.h: stb_image
// 2.27's HDR reader hangs on some truncated files), OpenEXR through OpenEXR's C core
// (image/exr.h). docs/design.md, "Images in", says why each.
// Integer images are sRGB-encoded and come back linear; float images are linear already
// (docs/scene-language.md, "Beyond project 4: textures, environment, lens").
//
// Decoders are guarded as the mesh importer is (docs/design.md, "Images in"): the size a
// header announces is checked against the limit on pixels and against what a file of this
// length can hold in its format before anything is decoded, and stb_image's own allocations
// run under a budget, so a short file cannot make it allocate gigabytes. What decoding takes
// (decode_bytes) must fit the caller's image memory (core/limits.h) and this process's memory
// (core/memory.h), and unless the user chose the image memory (`memory_chosen`), obey the
// decompression-bomb rule (decode_ratio_error), all checked from the header before anything is
// decoded; a file is read whole only once its first bytes are an image's magic number.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "raylane/core/error.h"
#include "raylane/core/limits.h"
#include "raylane/core/memory.h"
#include "raylane/image/image.h"
#include "raylane/image/texels.h"

namespace raylane {

inline constexpr uint64_t kMaxImageFileBytes = uint64_t(1) << 30;

enum class InputFormat { kPng, kJpeg, kBmp, kTga, kHdr, kPfm, kExr };

struct InputImageInfo {
  InputFormat format = InputFormat::kPng;
  uint32_t width = 0, height = 0;
  int channels = 0;       // as stored (1 grey … 4 RGBA); the reader keeps RGB
  bool is_float = false;  // HDR, PFM and EXR: linear; otherwise sRGB-encoded integers
  bool is_16bit = false;  // 16-bit PNG
};

std::string_view input_format_name(InputFormat f);

// The header only: format, size, channels; the same checks as decode_input_image makes before it
// decodes. `name` is the file's name, for the TGA fallback (TGA has no magic number).
// `file_bytes` is the whole file's length when `bytes` holds only its beginning.
Result<InputImageInfo> probe_input_image(std::string_view bytes, std::string_view name);
Result<InputImageInfo> probe_input_image(std::string_view bytes, std::string_view name,
                                         uint64_t file_bytes);
// The most bytes decoding an image of `info` from a file of `file_bytes` holds at once: the
// file, the decoder's buffers and the linear RGB floats it ends in.
uint64_t decode_bytes(const InputImageInfo& info, uint64_t file_bytes);
// What the scene keeps of an image: its texels in the form image/texels.h chooses (4 bytes a
// texel for 8-bit and Radiance HDR files; 12 for float files, which a header cannot tell to be
// halves, so 6 of them may turn out to be free).
uint64_t stored_texel_bytes(const InputImageInfo& info);
// The most bytes decoding to texels holds at once: the file, the decoder's buffers and the
// texels (for float files, the floats and their halves beside them).
uint64_t decode_texels_bytes(const InputImageInfo& info, uint64_t file_bytes);
// The whole image as linear RGB, top row first; alpha is dropped, grey becomes RGB. Pixels
// that are negative, NaN or infinite are an error, and so is an image whose decode_bytes are
// more than `memory_left` (the image memory not yet taken) or than this process can have.
Result<Image> decode_input_image(std::string_view bytes, std::string_view name,
                                 uint64_t memory_left = default_image_memory(),
                                 bool memory_chosen = false);

// The same image as compact texels (image/texels.h): what a scene keeps, and what decoding
// takes is decode_texels_bytes. The texels decode to exactly the floats decode_input_image
// returns.
Result<TexelImage> decode_input_texels(std::string_view bytes, std::string_view name,
                                       uint64_t memory_left = default_image_memory(),
                                       bool memory_chosen = false);

// A file, read through read_input_file (regular files only, kMaxImageFileBytes at most).
// Errors start with the path. The header is read from the file's first bytes; the whole file
// only when those do not hold it. The image is read whole only after its first bytes are an
// image's magic number and its length fits `memory_left`.
Result<InputImageInfo> read_input_image_info(const std::string& path,
                                             uint64_t memory_left = default_image_memory());
Result<Image> read_input_image(const std::string& path,
                               uint64_t memory_left = default_image_memory(),
                               bool memory_chosen = false);
Result<TexelImage> read_input_texels(const std::string& path,
                                     uint64_t memory_left = default_image_memory(),
                                     bool memory_chosen = false);

// "... (--image-memory MIB raises it)": the error for an image that does not fit.
std::string image_memory_error(uint64_t needed, uint64_t memory_left, std::string_view what);
// The decompression-bomb rule (core/limits.h, kMaxDecodeRatio): an error when decoding takes
// more than kBombFloorBytes and more than kMaxDecodeRatio times the file's bytes. `suffice` is
// the --image-memory figure, in bytes, that would read it.
std::optional<std::string> decode_ratio_error(uint64_t needed, uint64_t file_bytes,
                                              uint64_t suffice, std::string_view what);
// An --image-memory value in MiB that holds `bytes`: rounded up.
uint64_t image_memory_mib(uint64_t bytes);

// The sRGB transfer function's inverse (IEC 61966-2-1): encoded value in [0, 1] → linear.
double srgb_to_linear(double encoded);

}  // namespace raylane
