#include "image/jpeg_decode.h"

#include <csetjmp>
#include <cstdio>  // jpeglib.h needs FILE and size_t declared first
#include <cstring>

#include <jerror.h>
#include <jpeglib.h>

namespace raylane::jpeg {

namespace {

// libjpeg reports errors through a callback that must not return; the documented way out is a
// longjmp back to the caller (libjpeg's example.txt, "error handling"). Only C frames and this
// file's functions, which hold no object with a destructor, lie between setjmp and longjmp.
struct Session {
  jpeg_decompress_struct cinfo{};
  jpeg_error_mgr err{};
  jpeg_progress_mgr progress{};
  std::jmp_buf jump{};
  char message[JMSG_LENGTH_MAX] = {};
};

Session& session_of(j_common_ptr cinfo) {
  return *static_cast<Session*>(cinfo->client_data);
}

[[noreturn]] void fail(j_common_ptr cinfo) {
  Session& s = session_of(cinfo);
  (*cinfo->err->format_message)(cinfo, s.message);
  std::longjmp(s.jump, 1);
}

// Warnings (msg_level −1) mark corrupt data that libjpeg papers over, e.g. a truncated file
// decoded with grey filler: an error here, since a texture must not come back half made up.
// Extraneous bytes before a marker lose no pixel; real cameras write them, and viewers
// accept them. Trace messages (level ≥ 0) are ignored.
void on_message(j_common_ptr cinfo, int level) {
  if (level < 0 && cinfo->err->msg_code != JWRN_EXTRANEOUS_DATA) fail(cinfo);
}

void on_progress(j_common_ptr cinfo) {
  auto* d = reinterpret_cast<j_decompress_ptr>(cinfo);
  if (d->input_scan_number > kMaxJpegScans) {
    Session& s = session_of(cinfo);
    std::snprintf(s.message, sizeof s.message, "more than %d scans (the limit)", kMaxJpegScans);
    std::longjmp(s.jump, 1);
  }
}

void open(Session& s, std::string_view bytes, uint64_t budget_bytes) {
  s.cinfo.err = jpeg_std_error(&s.err);
  s.err.error_exit = fail;
  s.err.emit_message = on_message;
  s.cinfo.client_data = &s;
  jpeg_create_decompress(&s.cinfo);
  s.cinfo.mem->max_memory_to_use = long(budget_bytes);
  s.progress.progress_monitor = on_progress;
  s.cinfo.progress = &s.progress;
  jpeg_mem_src(&s.cinfo, reinterpret_cast<const unsigned char*>(bytes.data()),
               static_cast<unsigned long>(bytes.size()));
}

// After jpeg_read_header: the file's kind is one raylane decodes, or the reason it is not.
const char* unsupported(const jpeg_decompress_struct& c) {
  if (c.arith_code) return "arithmetic-coded JPEG is not supported";
  if (c.num_components != 1 && c.num_components != 3 &&
      !(c.num_components == 4 &&
        (c.jpeg_color_space == JCS_CMYK || c.jpeg_color_space == JCS_YCCK)))
    return "only grey, colour (YCbCr or RGB) and CMYK JPEG are supported";
  return nullptr;
}

// Inks to sRGB bytes, as the common viewers do it (no colour profile): each channel is
// (1 − ink)·(1 − black). Files with Adobe's APP14 marker store the inks inverted (Photoshop's
// convention: 255 means no ink), so there the channel is C·K/255 of the stored values; libjpeg
// hands CMYK over as stored.
void cmyk_to_rgb(const JSAMPLE* inks, uint32_t width, bool adobe_inverted, JSAMPLE* rgb) {
  for (uint32_t x = 0; x < width; ++x) {
    const JSAMPLE* p = inks + 4 * std::size_t(x);
    unsigned k = adobe_inverted ? p[3] : 255u - p[3];
    for (int c = 0; c < 3; ++c) {
      unsigned v = adobe_inverted ? p[c] : 255u - p[c];
      rgb[3 * std::size_t(x) + c] = JSAMPLE((v * k + 127) / 255);
    }
  }
}

// The setjmp frames: plain data only, so a longjmp out of libjpeg skips no destructor.
bool read_header(Session& s, std::string_view bytes, Header& out) {
  if (setjmp(s.jump)) return false;
  open(s, bytes, uint64_t(1) << 24);
  jpeg_read_header(&s.cinfo, TRUE);
  if (const char* why = unsupported(s.cinfo)) {
    std::snprintf(s.message, sizeof s.message, "%s", why);
    return false;
  }
  out.width = s.cinfo.image_width;
  out.height = s.cinfo.image_height;
  out.components = s.cinfo.num_components;
  return true;
}

bool read_pixels(Session& s, std::string_view bytes, const Header& h, uint64_t budget,
                 unsigned char* rgb) {
  if (setjmp(s.jump)) return false;
  open(s, bytes, budget);
  jpeg_read_header(&s.cinfo, TRUE);
  if (s.cinfo.image_width != h.width || s.cinfo.image_height != h.height ||
      unsupported(s.cinfo) != nullptr) {
    std::snprintf(s.message, sizeof s.message, "the header changed between two reads");
    return false;
  }
  const bool cmyk = s.cinfo.num_components == 4;
  // Grey is widened to RGB by libjpeg; YCCK becomes CMYK, which libjpeg leaves to us.
  s.cinfo.out_color_space = cmyk ? JCS_CMYK : JCS_RGB;
  jpeg_start_decompress(&s.cinfo);
  // A row of inks from libjpeg's own pool (freed with the session, within its budget).
  JSAMPARRAY inks = cmyk ? (*s.cinfo.mem->alloc_sarray)(reinterpret_cast<j_common_ptr>(&s.cinfo),
                                                        JPOOL_IMAGE, h.width * 4, 1)
                         : nullptr;
  const std::size_t row_bytes = std::size_t(h.width) * 3;
  while (s.cinfo.output_scanline < s.cinfo.output_height) {
    JSAMPROW row = rgb + std::size_t(s.cinfo.output_scanline) * row_bytes;
    if (!cmyk) {
      jpeg_read_scanlines(&s.cinfo, &row, 1);
      continue;
    }
    jpeg_read_scanlines(&s.cinfo, inks, 1);
    cmyk_to_rgb(inks[0], h.width, s.cinfo.saw_Adobe_marker != 0, row);
  }
  jpeg_finish_decompress(&s.cinfo);
  return true;
}

}  // namespace

bool probe(std::string_view bytes, Header& out, std::string& why) {
  Session s;
  bool ok = read_header(s, bytes, out);
  if (!ok) why = s.message;
  jpeg_destroy_decompress(&s.cinfo);
  return ok;
}

bool decode(std::string_view bytes, const Header& h, uint64_t budget_bytes,
            std::vector<uint8_t>& rgb, std::string& why) {
  rgb.assign(std::size_t(h.width) * h.height * 3, 0);
  Session s;
  bool ok = read_pixels(s, bytes, h, budget_bytes, rgb.data());
  if (!ok) why = s.message;
  jpeg_destroy_decompress(&s.cinfo);
  if (!ok) rgb.clear();
  return ok;
}

}  // namespace raylane::jpeg
