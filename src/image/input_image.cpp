#include "raylane/image/input_image.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "image/jpeg_decode.h"
#include "image/stb_decode.h"
#include "raylane/core/input_file.h"
#include "raylane/core/memory.h"
#include "raylane/core/strings.h"
#include "raylane/image/exr.h"
#include "raylane/image/pfm.h"
#include "raylane/image/rgbe.h"

namespace raylane {

namespace {

bool starts_with(std::string_view b, std::string_view magic) {
  return b.substr(0, magic.size()) == magic;
}

bool ends_with_tga(std::string_view name) {
  if (name.size() < 4) return false;
  std::string_view ext = name.substr(name.size() - 4);
  return ext[0] == '.' && (ext[1] | 0x20) == 't' && (ext[2] | 0x20) == 'g' &&
         (ext[3] | 0x20) == 'a';
}

// The format by its magic number; TGA, which has none, by the file's extension.
Result<InputFormat> format_of(std::string_view b, std::string_view name) {
  if (starts_with(b, "\x89PNG\r\n\x1a\n")) return InputFormat::kPng;
  if (starts_with(b, "\xff\xd8\xff")) return InputFormat::kJpeg;
  if (starts_with(b, "BM")) return InputFormat::kBmp;
  if (starts_with(b, "#?RADIANCE") || starts_with(b, "#?RGBE")) return InputFormat::kHdr;
  for (std::string_view magic : {"PF", "Pf"})  // colour, grey
    for (char space : {'\n', '\r', ' '})
      if (b.size() > 2 && b.substr(0, 2) == magic && b[2] == space) return InputFormat::kPfm;
  if (is_exr(b)) return InputFormat::kExr;
  if (ends_with_tga(name)) return InputFormat::kTga;
  return Error{"not an image raylane reads (PNG, JPEG, TGA, BMP, Radiance HDR, PFM or OpenEXR)"};
}

// The most pixels a file of the format can describe per byte of it, so that a header announcing
// more than the file can hold is refused before anything is decoded:
// - PNG: deflate expands at most 1032:1 (RFC 1951: a 258-byte match costs at least 2 bits), and
//   a pixel takes at least 1 bit (1-bit grey): 8·1032;
// - JPEG: every 8×8 block of the first component costs at least one bit (its DC code is a
//   Huffman code of length ≥ 1, ITU T.81 F.1.2.1): 64·8;
// - BMP (stb reads uncompressed ones only): 1 bit per pixel at least;
// - TGA: an RLE packet of 1 header byte and 1 pixel byte repeats up to 128 pixels;
// - Radiance HDR: a run of up to 127 bytes costs 2 bytes, in each of 4 components;
// - OpenEXR: probe_exr bounds the unpacked bytes per compression method itself; here only a
//   backstop for PIZ and DWA, which it cannot bound: a chunk of at most 256 lines costs at
//   least 16 bytes (offset table entry and chunk header), so a small file cannot be huge.
uint64_t max_pixels_per_byte(InputFormat f) {
  switch (f) {
    case InputFormat::kPng:
      return 8 * 1032;
    case InputFormat::kJpeg:
      return 64 * 8;
    case InputFormat::kBmp:
      return 8;
    case InputFormat::kTga:
      return 64;
    case InputFormat::kHdr:
      return 16;
    case InputFormat::kPfm:
      return 1;
    case InputFormat::kExr:
      return 1 << 16;
  }
  return 1;
}

Status check_size(const InputImageInfo& info, uint64_t file_bytes) {
  uint64_t pixels = uint64_t(info.width) * info.height;
  if (info.width == 0 || info.height == 0) return Error{"the image is empty (0 pixels)"};
  if (pixels > kMaxImagePixels)
    return Error{cat("the image has ", info.width, "x", info.height,
                     " pixels; the limit is 2^28 (268435456)")};
  // A small allowance covers headers and tiny images, whose few bytes are mostly header.
  if (pixels > max_pixels_per_byte(info.format) * file_bytes + 4096)
    return Error{cat("the header announces ", info.width, "x", info.height, " pixels, more than ",
                     file_bytes, " bytes of ", input_format_name(info.format), " can hold")};
  return ok_status();
}

Result<InputImageInfo> probe_stb(std::string_view bytes, InputFormat format) {
  stb::Header h;
  std::string why;
  if (!stb::probe(bytes, h, why))
    return Error{cat("unreadable ", input_format_name(format), " header: ", why)};
  InputImageInfo info;
  info.format = format;
  info.width = uint32_t(h.width), info.height = uint32_t(h.height);
  info.channels = h.channels;
  info.is_float = h.is_hdr;
  info.is_16bit = h.is_16bit;
  return info;
}

// Radiance HDR through our own RGBE reader (image/rgbe.h, fuzzed since it was written): stb_image
// 2.27's HDR reader loops for ever on a run-length scanline whose count byte is 0 (found by
// fuzz_image on a truncated file). decode_rgbe checks the announced size against the data
// before it allocates.
Result<Image> decode_hdr(std::string_view bytes) {
  auto file = decode_rgbe(bytes);
  if (!file) return Error{file.error()};
  return std::move(file->image);
}

// The header alone: `raylane info` and the memory check before decoding read no pixel.
Result<InputImageInfo> probe_hdr(std::string_view bytes) {
  auto size = probe_rgbe(bytes);
  if (!size) return Error{size.error()};
  InputImageInfo info;
  info.format = InputFormat::kHdr;
  info.width = size->width, info.height = size->height;
  info.channels = 3;
  info.is_float = true;
  return info;
}

Result<InputImageInfo> probe_openexr(std::string_view bytes) {
  auto h = probe_exr(bytes);
  if (!h) return Error{h.error()};
  if (!h->has_rgb && !h->has_y) return Error{"the EXR file has no R, G, B or Y channel"};
  InputImageInfo info;
  info.format = InputFormat::kExr;
  info.width = h->width, info.height = h->height;
  info.channels = h->has_rgb ? 3 : 1;
  info.is_float = true;
  return info;
}

Result<InputImageInfo> probe_jpeg(std::string_view bytes) {
  jpeg::Header h;
  std::string why;
  if (!jpeg::probe(bytes, h, why)) return Error{cat("unreadable JPEG header: ", why)};
  InputImageInfo info;
  info.format = InputFormat::kJpeg;
  info.width = h.width, info.height = h.height;
  info.channels = h.components;
  return info;
}

Result<InputImageInfo> probe_pfm(std::string_view bytes) {
  auto h = parse_pfm_header(bytes);
  if (!h) return Error{h.error()};
  InputImageInfo info;
  info.format = InputFormat::kPfm;
  info.width = h->width, info.height = h->height;
  info.channels = h->channels;
  info.is_float = true;
  return info;
}

Result<Image> to_linear(const InputImageInfo& info, const stb::Pixels& px) {
  Image img(info.width, info.height);
  const std::size_t n = img.rgb.size();
  if (info.is_float) {
    for (std::size_t i = 0; i < n; ++i)
      img.rgb[i] = px.f32[i];
  } else if (info.is_16bit) {
    for (std::size_t i = 0; i < n; ++i)
      img.rgb[i] = float(srgb_to_linear(px.u16[i] / 65535.0));
  } else {
    const auto& table = srgb8_table();
    for (std::size_t i = 0; i < n; ++i)
      img.rgb[i] = table[px.u8[i]];
  }
  return img;
}

// The 8- and 16-bit samples (or stb's floats) of a JPEG, PNG, BMP or TGA file, 3 a pixel.
// libjpeg's memory: a progressive file keeps every coefficient (2 bytes each, 64 per 8×8 block
// and component: 6 bytes per pixel at 4:4:4), plus row buffers; 16 bytes per pixel bound it.
// stb holds the file's compressed data, the decoded samples in their stored channels and then
// in 3, each at most twice over while its buffer grows: 8 samples of 4 bytes per pixel and 4
// bytes per file byte bound all of that.
Result<stb::Pixels> decode_samples(std::string_view bytes, const InputImageInfo& info) {
  stb::Pixels px;
  std::string why;
  if (info.format == InputFormat::kJpeg) {
    jpeg::Header h{info.width, info.height, info.channels};
    uint64_t budget = uint64_t(info.width) * info.height * 16 + (1u << 20);
    if (!jpeg::decode(bytes, h, budget, px.u8, why))
      return Error{cat("cannot decode the JPEG data: ", why)};
    return px;
  }
  stb::Header h{int(info.width), int(info.height), info.channels, info.is_16bit, info.is_float};
  uint64_t budget = uint64_t(info.width) * info.height * 32 + 4 * bytes.size() + (1u << 20);
  if (!stb::decode(bytes, h, budget, px, why))
    return Error{cat("cannot decode the ", input_format_name(info.format), " data: ", why)};
  return px;
}

// 8-bit sRGB samples, kept as they are (image/texels.h): every format stb or libjpeg decodes
// but 16-bit PNG and stb's float formats.
bool stored_as_srgb8(const InputImageInfo& info) {
  return !info.is_float && !info.is_16bit && info.format != InputFormat::kHdr &&
         info.format != InputFormat::kPfm && info.format != InputFormat::kExr;
}

Status check_pixels(const Image& img) {
  for (std::size_t i = 0; i < img.rgb.size(); ++i) {
    float v = img.rgb[i];
    if (!(v >= 0) || !std::isfinite(v)) {
      std::size_t pixel = i / 3;
      return Error{cat("pixel (", pixel % img.width, ", ", pixel / img.width, ") is ", v,
                       ": image values must be finite and >= 0")};
    }
  }
  return ok_status();
}

}  // namespace

std::string_view input_format_name(InputFormat f) {
  switch (f) {
    case InputFormat::kPng:
      return "PNG";
    case InputFormat::kJpeg:
      return "JPEG";
    case InputFormat::kBmp:
      return "BMP";
    case InputFormat::kTga:
      return "TGA";
    case InputFormat::kHdr:
      return "Radiance HDR";
    case InputFormat::kPfm:
      return "PFM";
    case InputFormat::kExr:
      return "OpenEXR";
  }
  return "image";
}

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

Result<InputImageInfo> probe_input_image(std::string_view bytes, std::string_view name) {
  return probe_input_image(bytes, name, bytes.size());
}

Result<InputImageInfo> probe_input_image(std::string_view bytes, std::string_view name,
                                         uint64_t file_bytes) {
  if (file_bytes == 0) return Error{"the file is empty"};
  if (file_bytes > kMaxImageFileBytes) return Error{"the file is larger than 1 GiB"};
  auto format = format_of(bytes, name);
  if (!format) return Error{format.error()};
  auto info = *format == InputFormat::kPfm    ? probe_pfm(bytes)
              : *format == InputFormat::kJpeg ? probe_jpeg(bytes)
              : *format == InputFormat::kHdr  ? probe_hdr(bytes)
              : *format == InputFormat::kExr  ? probe_openexr(bytes)
                                              : probe_stb(bytes, *format);
  if (!info) return info;
  if (auto s = check_size(*info, file_bytes); !s) return Error{s.error()};
  return info;
}

// Per pixel, besides the 12 bytes of linear RGB floats the image ends in (and the file):
// - stb_image (PNG, BMP, TGA): its samples as stored and converted to 3 channels, then our
//   copy of those: 4 + 3 samples (1, 2 or 4 bytes each);
// - JPEG: libjpeg's coefficients of a progressive file at 4:4:4 (2 bytes × 64 per 8×8 block
//   and component: 6) and its 3-byte output rows;
// - Radiance HDR: the 4 RGBE bytes of a row at a time, but the float image is built in place:
//   4 bytes, counted per pixel to stay on the safe side;
// - PFM: none beyond the floats; OpenEXR: every channel unpacked as float (4 channels).
uint64_t decode_bytes(const InputImageInfo& info, uint64_t file_bytes) {
  uint64_t pixels = uint64_t(info.width) * info.height;
  uint64_t sample = info.is_float ? 4 : info.is_16bit ? 2 : 1;
  uint64_t working = 0;
  switch (info.format) {
    case InputFormat::kPng:
    case InputFormat::kBmp:
    case InputFormat::kTga:
      working = 7 * sample;
      break;
    case InputFormat::kJpeg:
      working = 9;
      break;
    case InputFormat::kHdr:
      working = 4;
      break;
    case InputFormat::kPfm:
      working = 0;
      break;
    case InputFormat::kExr:
      working = 16;
      break;
  }
  return file_bytes + pixels * (12 + working);
}

std::string image_memory_error(uint64_t needed, uint64_t memory_left, std::string_view what) {
  return cat(what, " takes ", bytes_text(needed), "; the image memory left is ",
             bytes_text(memory_left), " (--image-memory MIB raises it)");
}

uint64_t image_memory_mib(uint64_t bytes) {
  return (bytes + (uint64_t(1) << 20) - 1) >> 20;
}

std::optional<std::string> decode_ratio_error(uint64_t needed, uint64_t file_bytes,
                                              uint64_t suffice, std::string_view what) {
  if (needed <= kBombFloorBytes || needed / std::max<uint64_t>(file_bytes, 1) <= kMaxDecodeRatio)
    return std::nullopt;
  return cat(what, " takes ", bytes_text(needed), " from a file of ", file_bytes, " bytes",
             ", more than ", kMaxDecodeRatio,
             " times its size, as only decompression bombs and nearly blank images do; "
             "--image-memory ",
             image_memory_mib(suffice), " reads it");
}

namespace {

// The probe and the memory check both decoders start with.
Result<InputImageInfo> probe_within(std::string_view bytes, std::string_view name,
                                    uint64_t memory_left, bool memory_chosen, bool texels) {
  auto info = probe_input_image(bytes, name);
  if (!info) return info;
  uint64_t needed =
      texels ? decode_texels_bytes(*info, bytes.size()) : decode_bytes(*info, bytes.size());
  std::string what = cat("decoding its ", info->width, "x", info->height, " pixels");
  if (!memory_chosen)
    if (auto bomb = decode_ratio_error(needed, bytes.size(), needed, what)) return Error{*bomb};
  if (needed > memory_left) return Error{image_memory_error(needed, memory_left, what)};
  if (Status s = check_memory(needed, what); !s) return Error{s.error()};
  return info;
}

// Every format as linear float RGB.
Result<Image> decode_floats(std::string_view bytes, const InputImageInfo& info) {
  Result<Image> img = Error{""};
  if (info.format == InputFormat::kPfm) {
    img = decode_pfm(bytes);
  } else if (info.format == InputFormat::kHdr) {
    img = decode_hdr(bytes);
  } else if (info.format == InputFormat::kExr) {
    img = decode_exr(bytes);
  } else {
    auto px = decode_samples(bytes, info);
    if (!px) return Error{px.error()};
    img = to_linear(info, *px);
  }
  if (!img) return img;
  if (auto s = check_pixels(*img); !s) return Error{s.error()};
  return img;
}

}  // namespace

uint64_t stored_texel_bytes(const InputImageInfo& info) {
  uint64_t pixels = uint64_t(info.width) * info.height;
  bool packed = stored_as_srgb8(info) || info.format == InputFormat::kHdr;
  return pixels * (packed ? 4 : 12);
}

uint64_t decode_texels_bytes(const InputImageInfo& info, uint64_t file_bytes) {
  uint64_t pixels = uint64_t(info.width) * info.height;
  if (info.format == InputFormat::kHdr)  // one row of RGBE planes besides the texels
    return file_bytes + stored_texel_bytes(info) + 4 * uint64_t(info.width);
  if (stored_as_srgb8(info)) {  // the samples as decode_bytes counts them, then 4 bytes each
    uint64_t working = info.format == InputFormat::kJpeg ? 9 : 7;
    return file_bytes + pixels * (working + 4);
  }
  // The floats, then their halves beside them while they are made.
  return decode_bytes(info, file_bytes) + pixels * 6;
}

Result<Image> decode_input_image(std::string_view bytes, std::string_view name,
                                 uint64_t memory_left, bool memory_chosen) {
  auto info = probe_within(bytes, name, memory_left, memory_chosen, false);
  if (!info) return Error{info.error()};
  return decode_floats(bytes, *info);
}

Result<TexelImage> decode_input_texels(std::string_view bytes, std::string_view name,
                                       uint64_t memory_left, bool memory_chosen) {
  auto info = probe_within(bytes, name, memory_left, memory_chosen, true);
  if (!info) return Error{info.error()};
  if (info->format == InputFormat::kHdr) return decode_rgbe_texels(bytes);
  if (stored_as_srgb8(*info)) {
    auto px = decode_samples(bytes, *info);
    if (!px) return Error{px.error()};
    return srgb8_texels(info->width, info->height, px->u8);
  }
  auto img = decode_floats(bytes, *info);
  if (!img) return Error{img.error()};
  return float_texels(std::move(*img));
}

namespace {

// Enough for every header raylane reads but JPEG's after long APP segments (a JPEG's EXIF
// thumbnail may take 64 KiB before the frame header): those are probed on the whole file.
constexpr uint64_t kHeadBytes = 64 << 10;

// The file's first bytes, once they are known to begin an image, and the file's length.
struct ImageHead {
  std::string bytes;
  uint64_t file_bytes = 0;
};

Result<ImageHead> read_image_head(const std::string& path) {
  auto size = regular_file_size(path);
  if (!size) return Error{cat(path, ": cannot read the image: ", size.error())};
  auto head = read_input_head(path, kHeadBytes, "the image");
  if (!head) return Error{head.error()};
  if (head->empty()) return Error{cat(path, ": the file is empty")};
  if (auto f = format_of(*head, path); !f) return Error{cat(path, ": ", f.error())};
  return ImageHead{std::move(*head), *size};
}

// The whole file, if it fits the image memory left.
Result<std::string> read_whole_image(const std::string& path, uint64_t file_bytes,
                                     uint64_t memory_left) {
  if (file_bytes > memory_left && file_bytes <= kMaxImageFileBytes)
    return Error{cat(path, ": ", image_memory_error(file_bytes, memory_left, "reading the file"))};
  return read_input_file(path, kMaxImageFileBytes, "the image");
}

}  // namespace

Result<InputImageInfo> read_input_image_info(const std::string& path, uint64_t memory_left) {
  auto head = read_image_head(path);
  if (!head) return Error{head.error()};
  auto info = probe_input_image(head->bytes, path, head->file_bytes);
  if (!info && head->bytes.size() < head->file_bytes) {
    auto bytes = read_whole_image(path, head->file_bytes, memory_left);
    if (!bytes) return Error{bytes.error()};
    info = probe_input_image(*bytes, path);
  }
  if (!info) return Error{cat(path, ": ", info.error())};
  return info;
}

namespace {

template <class Decode>
auto read_and_decode(const std::string& path, uint64_t memory_left, Decode decode)
    -> decltype(decode(std::string_view(), path)) {
  auto head = read_image_head(path);
  if (!head) return Error{head.error()};
  auto bytes = read_whole_image(path, head->file_bytes, memory_left);
  if (!bytes) return Error{bytes.error()};
  auto img = decode(*bytes, path);
  if (!img) return Error{cat(path, ": ", img.error())};
  return img;
}

}  // namespace

Result<Image> read_input_image(const std::string& path, uint64_t memory_left, bool memory_chosen) {
  return read_and_decode(path, memory_left, [&](std::string_view b, std::string_view n) {
    return decode_input_image(b, n, memory_left, memory_chosen);
  });
}

Result<TexelImage> read_input_texels(const std::string& path, uint64_t memory_left,
                                     bool memory_chosen) {
  return read_and_decode(path, memory_left, [&](std::string_view b, std::string_view n) {
    return decode_input_texels(b, n, memory_left, memory_chosen);
  });
}

}  // namespace raylane
