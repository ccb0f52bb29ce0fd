// Reading EXR files (OpenEXRCore: error codes, and the header is ours to check before
// decoding). Writing is in exr_write.cpp.
#include "raylane/image/exr.h"

#include <OpenEXR/openexr.h>
#include <sys/types.h>

#include <algorithm>
#include <cstring>
#include <exception>

#include "image/exr_rgba.h"
#include "raylane/core/limits.h"
#include "raylane/core/strings.h"

namespace raylane {

namespace {

// The message of the last error OpenEXRCore reported on this thread (its default handler
// would print to stderr).
thread_local std::string core_message;

void remember_error(exr_const_context_t, exr_result_t, const char* msg) {
  core_message = msg ? msg : "";
}

int64_t read_from_memory(exr_const_context_t, void* user, void* buffer, uint64_t size,
                         uint64_t offset, exr_stream_error_func_ptr_t) {
  auto* bytes = static_cast<const std::string_view*>(user);
  if (offset >= bytes->size()) return 0;
  uint64_t n = std::min<uint64_t>(size, bytes->size() - offset);
  std::memcpy(buffer, bytes->data() + offset, n);
  return int64_t(n);
}

int64_t memory_size(exr_const_context_t, void* user) {
  return int64_t(static_cast<const std::string_view*>(user)->size());
}

std::string core_error(exr_result_t rv) {
  return core_message.empty() ? exr_get_default_error_message(rv) : core_message;
}

// An open read context over bytes in memory.
class CoreFile {
 public:
  explicit CoreFile(std::string_view bytes) : bytes_(bytes) {}
  ~CoreFile() {
    if (ctxt_) exr_finish(&ctxt_);
  }
  CoreFile(const CoreFile&) = delete;
  CoreFile& operator=(const CoreFile&) = delete;

  Status open() {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = remember_error;
    init.user_data = &bytes_;
    init.read_fn = read_from_memory;
    init.size_fn = memory_size;  // lets the core check offsets against the file's length
    init.max_image_width = int(kMaxImagePixels);
    init.max_image_height = int(kMaxImagePixels);
    // A damaged chunk table is an error, not a search through the file for chunks.
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    core_message.clear();
    exr_result_t rv = exr_start_read(&ctxt_, "input.exr", &init);
    if (rv != EXR_ERR_SUCCESS) return Error{cat("unreadable EXR header: ", core_error(rv))};
    return ok_status();
  }
  exr_context_t get() const { return ctxt_; }
  uint64_t size() const { return bytes_.size(); }

 private:
  std::string_view bytes_;
  exr_context_t ctxt_ = nullptr;
};

// The header facts the decoder needs beside ExrInfo.
struct Layout {
  ExrInfo info;
  exr_attr_box2i_t window{};
  const exr_attr_chlist_t* channels = nullptr;
};

// The most bytes of unpacked pixel data one byte of compressed data can give, where the
// method bounds it: none 1; RLE 64 (a 2-byte run codes at most 128 bytes); ZIP, ZIPS and
// PXR24 (zlib) 1032, deflate's limit (RFC 1951: a 258-byte match costs at least 2 bits);
// B44 and B44A 32/3 (a 4×4 block of halves, 32 bytes, in 3 bytes at best). PIZ and DWA have
// no simple bound; 2^18 is far above what either reaches on a flat image (DWA keeps a DC value
// per 8×8 block, zlib-compressed: about 64·2·1032), so it refuses only files far too short.
uint64_t max_expansion(exr_compression_t c) {
  switch (c) {
    case EXR_COMPRESSION_NONE:
      return 1;
    case EXR_COMPRESSION_RLE:
      return 64;
    case EXR_COMPRESSION_ZIPS:
    case EXR_COMPRESSION_ZIP:
    case EXR_COMPRESSION_PXR24:
      return 1032;
    case EXR_COMPRESSION_B44:
    case EXR_COMPRESSION_B44A:
      return 11;
    default:
      return uint64_t(1) << 18;
  }
}

// Every sample of every channel, unpacked, at most 4 GiB: the decoder's buffers and time
// are bounded by it.
constexpr uint64_t kMaxUnpackedBytes = uint64_t(1) << 32;

Status check_data(const CoreFile& f, const Layout& l) {
  exr_context_t c = f.get();
  int32_t chunks = 0;
  exr_compression_t compression{};
  if (exr_get_chunk_count(c, 0, &chunks) != EXR_ERR_SUCCESS ||
      exr_get_compression(c, 0, &compression) != EXR_ERR_SUCCESS)
    return Error{"bad EXR header: no chunk count or compression"};
  // Each chunk has an 8-byte entry in the offset table and an 8-byte header (y, size).
  if (chunks <= 0 || uint64_t(chunks) > f.size() / 16)
    return Error{cat("the EXR header announces ", chunks, " chunks, more than ", f.size(),
                     " bytes can hold")};
  uint64_t unpacked = 0;
  const uint64_t w = l.info.width, h = l.info.height;
  for (int i = 0; i < l.channels->num_channels; ++i) {
    const exr_attr_chlist_entry_t& e = l.channels->entries[i];
    if (e.x_sampling < 1 || e.y_sampling < 1) return Error{"bad EXR channel sampling"};
    uint64_t bytes = e.pixel_type == EXR_PIXEL_HALF ? 2 : 4;
    unpacked +=
        (w + e.x_sampling - 1) / e.x_sampling * ((h + e.y_sampling - 1) / e.y_sampling) * bytes;
  }
  if (unpacked > kMaxUnpackedBytes)
    return Error{cat("the EXR pixels take ", unpacked, " bytes unpacked; the limit is 4 GiB")};
  // A small allowance covers tiny images, whose few bytes are mostly header.
  if (unpacked > max_expansion(compression) * f.size() + 4096)
    return Error{cat("the EXR header announces ", unpacked, " bytes of pixels, more than ",
                     f.size(), " bytes of its compression can hold")};
  return ok_status();
}

// The text of a string the core parsed (empty if it has none).
std::string_view text_of(const exr_attr_string_t& s) {
  if (!s.str || s.length <= 0) return {};
  return std::string_view(s.str, std::size_t(s.length));
}

std::string layer_of(std::string_view channel) {
  std::size_t dot = channel.rfind('.');
  return std::string(dot == std::string_view::npos ? std::string_view() : channel.substr(0, dot));
}

void collect_metadata(const CoreFile& f, ExrInfo& info) {
  int32_t count = 0;
  if (exr_get_attribute_count(f.get(), 0, &count) != EXR_ERR_SUCCESS) return;
  for (int32_t i = 0; i < count; ++i) {
    const exr_attribute_t* a = nullptr;
    if (exr_get_attribute_by_index(f.get(), 0, EXR_ATTR_LIST_FILE_ORDER, i, &a) !=
            EXR_ERR_SUCCESS ||
        !a || !a->name || a->type != EXR_ATTR_STRING || !a->string)
      continue;
    info.metadata.push_back(cat(a->name, "=", text_of(*a->string)));
  }
}

Result<Layout> read_layout(const CoreFile& f) {
  exr_context_t c = f.get();
  int parts = 0;
  exr_storage_t storage{};
  if (exr_get_count(c, &parts) != EXR_ERR_SUCCESS || parts != 1)
    return Error{"multi-part EXR files are not read (one part only)"};
  if (exr_get_storage(c, 0, &storage) != EXR_ERR_SUCCESS || storage != EXR_STORAGE_SCANLINE)
    return Error{"tiled and deep EXR files are not read (scanline images only)"};
  Layout l;
  if (exr_get_data_window(c, 0, &l.window) != EXR_ERR_SUCCESS ||
      exr_get_channels(c, 0, &l.channels) != EXR_ERR_SUCCESS || !l.channels)
    return Error{"bad EXR header: no data window or channels"};
  int64_t w = int64_t(l.window.max.x) - l.window.min.x + 1;
  int64_t h = int64_t(l.window.max.y) - l.window.min.y + 1;
  if (w <= 0 || h <= 0) return Error{"the EXR image is empty (0 pixels)"};
  if (uint64_t(w) * uint64_t(h) > kMaxImagePixels)
    return Error{cat("the EXR image has ", w, "x", h, " pixels; the limit is 2^28 (268435456)")};
  l.info.width = uint32_t(w), l.info.height = uint32_t(h);
  if (Status s = check_data(f, l); !s) return Error{s.error()};
  for (int i = 0; i < l.channels->num_channels; ++i) {
    std::string name(text_of(l.channels->entries[i].name));
    l.info.channels.push_back(name);
    std::string layer = layer_of(name);
    if (std::find(l.info.layers.begin(), l.info.layers.end(), layer) == l.info.layers.end())
      l.info.layers.push_back(layer);
  }
  std::stable_partition(l.info.layers.begin(), l.info.layers.end(),
                        [](const std::string& s) { return s.empty(); });
  auto has = [&](const char* n) {
    return std::find(l.info.channels.begin(), l.info.channels.end(), n) != l.info.channels.end();
  };
  l.info.has_rgb = has("R") && has("G") && has("B");
  l.info.has_y = has("Y");
  collect_metadata(f, l.info);
  return l;
}

// Decodes the channels named in `wanted` into one interleaved float buffer, top row first.
class ChunkDecoder {
 public:
  ChunkDecoder(const CoreFile& f, const Layout& l, const std::vector<std::string>& wanted)
      : f_(f), l_(l), wanted_(wanted) {}
  ~ChunkDecoder() {
    if (started_) exr_decoding_destroy(f_.get(), &dec_);
  }
  ChunkDecoder(const ChunkDecoder&) = delete;
  ChunkDecoder& operator=(const ChunkDecoder&) = delete;

  Result<std::vector<float>> run() {
    if (Status s = check_wanted(); !s) return Error{s.error()};
    int32_t lines = 0;
    if (exr_get_scanlines_per_chunk(f_.get(), 0, &lines) != EXR_ERR_SUCCESS || lines <= 0)
      return Error{"bad EXR header: no scanlines per chunk"};
    out_.assign(std::size_t(l_.info.width) * l_.info.height * wanted_.size(), 0.0f);
    for (int64_t y = l_.window.min.y; y <= l_.window.max.y; y += lines)
      if (Status s = decode_chunk(int(y)); !s) return Error{s.error()};
    return std::move(out_);
  }

 private:
  // Subsampled and integer channels are not converted to the float pixels raylane keeps. A
  // subsampled channel beside them is refused too: OpenEXRCore 3.1 decodes a wanted channel
  // with the right half of each row left 0 when two subsampled ones are skipped (a
  // luminance-chroma file's Y beside RY and BY); decode_exr reads such files through OpenEXR's
  // RGBA interface instead.
  Status check_wanted() const {
    for (int i = 0; i < l_.channels->num_channels; ++i) {
      const exr_attr_chlist_entry_t& e = l_.channels->entries[i];
      if (e.x_sampling != 1 || e.y_sampling != 1)
        return Error{cat("EXR channel ", text_of(e.name),
                         " is subsampled; raylane reads the colour of such files (R, G, B or "
                         "luminance-chroma), not their layers")};
    }
    for (const std::string& name : wanted_) {
      for (int i = 0; i < l_.channels->num_channels; ++i) {
        const exr_attr_chlist_entry_t& e = l_.channels->entries[i];
        if (name != text_of(e.name)) continue;
        if (e.x_sampling != 1 || e.y_sampling != 1)
          return Error{cat("EXR channel ", name, " is subsampled; raylane reads full channels")};
        if (e.pixel_type != EXR_PIXEL_HALF && e.pixel_type != EXR_PIXEL_FLOAT)
          return Error{cat("EXR channel ", name, " holds integers; raylane reads half or float")};
      }
    }
    return ok_status();
  }

  Status fail(exr_result_t rv, int y) const {
    return Error{cat("cannot decode the EXR scanlines at y = ", y, ": ", core_error(rv))};
  }

  Status decode_chunk(int y) {
    exr_chunk_info_t ci{};
    core_message.clear();
    exr_result_t rv = exr_read_scanline_chunk_info(f_.get(), 0, y, &ci);
    if (rv != EXR_ERR_SUCCESS) return fail(rv, y);
    if (ci.start_y < l_.window.min.y || int64_t(ci.start_y) + ci.height - 1 > l_.window.max.y ||
        ci.height <= 0 || ci.width != int32_t(l_.info.width))
      return Error{cat("EXR chunk at y = ", y, " does not fit the data window")};
    rv = started_ ? exr_decoding_update(f_.get(), 0, &ci, &dec_)
                  : exr_decoding_initialize(f_.get(), 0, &ci, &dec_);
    if (rv != EXR_ERR_SUCCESS) return fail(rv, y);
    started_ = true;
    point_channels(ci);
    rv = exr_decoding_choose_default_routines(f_.get(), 0, &dec_);
    if (rv == EXR_ERR_SUCCESS) rv = exr_decoding_run(f_.get(), 0, &dec_);
    if (rv != EXR_ERR_SUCCESS) return fail(rv, y);
    return ok_status();
  }

  // Wanted channels go to their place in the interleaved buffer as float. The others are
  // decoded too, into a scratch buffer: OpenEXRCore 3.1.5 writes through the null pointer that
  // is documented to skip a channel (found by fuzz_image on its seed of a half file whose
  // layer alone was read; Exr.HalfLayersAreReadBack keeps that case). All outputs are 4 bytes
  // wide, which also keeps the core off its shortcuts for all-16-bit outputs.
  void point_channels(const exr_chunk_info_t& ci) {
    const std::size_t n = wanted_.size(), w = l_.info.width;
    std::size_t scratch = 0;
    for (int c = 0; c < dec_.channel_count; ++c)
      if (!is_wanted(dec_.channels[c]))
        scratch += std::size_t(std::max(dec_.channels[c].width, 0)) *
                   std::size_t(std::max(dec_.channels[c].height, 0));
    scratch_.resize(std::max(scratch_.size(), scratch));
    std::size_t used = 0;
    for (int c = 0; c < dec_.channel_count; ++c) {
      exr_coding_channel_info_t& ch = dec_.channels[c];
      ch.user_bytes_per_element = 4;
      ch.user_data_type = ch.data_type == EXR_PIXEL_UINT ? EXR_PIXEL_UINT : EXR_PIXEL_FLOAT;
      auto it = std::find(wanted_.begin(), wanted_.end(), ch.channel_name);
      if (it == wanted_.end()) {
        ch.decode_to_ptr = reinterpret_cast<uint8_t*>(scratch_.data() + used);
        ch.user_pixel_stride = 4;
        ch.user_line_stride = int32_t(std::max(ch.width, 0) * 4);
        used += std::size_t(std::max(ch.width, 0)) * std::size_t(std::max(ch.height, 0));
        continue;
      }
      std::size_t k = std::size_t(it - wanted_.begin());
      std::size_t row = std::size_t(ci.start_y - l_.window.min.y);
      ch.decode_to_ptr = reinterpret_cast<uint8_t*>(&out_[(row * w) * n + k]);
      ch.user_pixel_stride = int32_t(n * sizeof(float));
      ch.user_line_stride = int32_t(w * n * sizeof(float));
    }
  }

  bool is_wanted(const exr_coding_channel_info_t& ch) const {
    return std::find(wanted_.begin(), wanted_.end(), ch.channel_name) != wanted_.end();
  }

  const CoreFile& f_;
  const Layout& l_;
  const std::vector<std::string>& wanted_;
  // Value-initialised: what EXR_DECODE_PIPELINE_INITIALIZER ({0}) does, without clang's
  // -Wmissing-field-initializers on the macro.
  exr_decode_pipeline_t dec_{};
  bool started_ = false;
  std::vector<float> out_;
  std::vector<float> scratch_;  // the channels not asked for, one chunk at a time
};

bool has_subsampled(const Layout& l) {
  for (int i = 0; i < l.channels->num_channels; ++i)
    if (l.channels->entries[i].x_sampling != 1 || l.channels->entries[i].y_sampling != 1)
      return true;
  return false;
}

// Opens, checks and decodes: every exception (std::bad_alloc above all) becomes an error.
template <class F>
auto guarded(F&& body) -> decltype(body()) {
  try {
    return body();
  } catch (const std::exception& e) {
    return Error{cat("EXR error: ", e.what())};
  }
}

Result<std::vector<float>> decode_channels(const CoreFile& f, const Layout& l,
                                           const std::vector<std::string>& wanted) {
  // A layer of many channels at the pixel limit would need more than the unpacked cap.
  if (uint64_t(l.info.width) * l.info.height * wanted.size() * sizeof(float) > kMaxUnpackedBytes)
    return Error{"the EXR channels asked for take more than 4 GiB as float"};
  ChunkDecoder decoder(f, l, wanted);
  return decoder.run();
}

}  // namespace

bool is_exr(std::string_view bytes) {
  return bytes.substr(0, 4) == std::string_view("\x76\x2f\x31\x01", 4);
}

Result<ExrInfo> probe_exr(std::string_view bytes) {
  return guarded([&]() -> Result<ExrInfo> {
    CoreFile f(bytes);
    if (Status s = f.open(); !s) return Error{s.error()};
    auto l = read_layout(f);
    if (!l) return Error{l.error()};
    return std::move(l->info);
  });
}

Result<Image> decode_exr(std::string_view bytes) {
  return guarded([&]() -> Result<Image> {
    CoreFile f(bytes);
    if (Status s = f.open(); !s) return Error{s.error()};
    auto l = read_layout(f);
    if (!l) return Error{l.error()};
    if (!l->info.has_rgb && !l->info.has_y)
      return Error{"the EXR file has no R, G, B or Y channel"};
    if (has_subsampled(*l)) {
      // OpenEXR's C++ reader parses the header again: a damaged header it reads differently
      // from the core reader (a fuzzer found one) is refused before it allocates by its window
      // (exr_rgba.cpp, window_problem), and a decode at another size is not handed on.
      auto img = exr_detail::decode_rgba_interface(bytes, l->info.width, l->info.height);
      if (img && (img->width != l->info.width || img->height != l->info.height))
        return Error{cat("the EXR header reads as ", l->info.width, "x", l->info.height, " and as ",
                         img->width, "x", img->height, "; the file is damaged")};
      return img;
    }
    std::vector<std::string> wanted =
        l->info.has_rgb ? std::vector<std::string>{"R", "G", "B"} : std::vector<std::string>{"Y"};
    auto data = decode_channels(f, *l, wanted);
    if (!data) return Error{data.error()};
    Image img;
    img.width = l->info.width, img.height = l->info.height;
    if (l->info.has_rgb) {
      img.rgb = std::move(*data);
    } else {  // grey: Y into all three
      img.rgb.resize(data->size() * 3);
      for (std::size_t i = 0; i < data->size(); ++i)
        img.rgb[3 * i] = img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = (*data)[i];
    }
    return img;
  });
}

Result<ExrLayer> decode_exr_layer(std::string_view bytes, std::string_view layer) {
  return guarded([&]() -> Result<ExrLayer> {
    CoreFile f(bytes);
    if (Status s = f.open(); !s) return Error{s.error()};
    auto l = read_layout(f);
    if (!l) return Error{l.error()};
    ExrLayer out;
    out.name = std::string(layer);
    std::vector<std::string> wanted;
    for (const std::string& c : l->info.channels) {
      if (layer_of(c) != layer) continue;
      wanted.push_back(c);
      out.channels.push_back(layer.empty() ? c : c.substr(layer.size() + 1));
    }
    if (wanted.empty()) return Error{cat("the EXR file has no layer ", in_quotes(layer))};
    auto data = decode_channels(f, *l, wanted);
    if (!data) return Error{data.error()};
    out.data = std::move(*data);
    return out;
  });
}

}  // namespace raylane
