// The one translation unit that compiles stb_image (Sean Barrett's public-domain decoder, from
// Debian's libstb-dev): static functions, so nothing clashes with libstb.so, and compiled by us,
// so the sanitizer and fuzzer builds instrument it. Only PNG, BMP and TGA are built (JPEG:
// src/image/input_image.cpp says why not): Radiance HDR goes through our own reader
// (src/image/input_image.cpp, decode_hdr).
#include "image/stb_decode.h"

#include <climits>
#include <cstdlib>
#include <cstring>

namespace {

// What stb_image may still allocate during the current call on this thread. Counted
// cumulatively (frees give nothing back), which over-counts the growth of a buffer that doubles
// by at most 2×: the budget allows for that.
thread_local uint64_t g_budget_left = 0;

// Zeroed: stb's TGA reader ignores a short read of an uncompressed row (stbi__getn's result),
// so a truncated file would leave rows of whatever the heap held; zeroed, they are black, the
// same on every decode (the image fuzzer found two decodes of one file that differed).
void* budget_malloc(std::size_t n) {
  if (n > g_budget_left) return nullptr;
  g_budget_left -= n;
  return std::calloc(1, n);
}

void* budget_realloc(void* p, std::size_t n) {
  if (n > g_budget_left) return nullptr;
  g_budget_left -= n;
  return std::realloc(p, n);
}

}  // namespace

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO
#define STBI_ONLY_PNG
#define STBI_ONLY_BMP
#define STBI_ONLY_TGA
#define STBI_MALLOC(n) budget_malloc(n)
#define STBI_REALLOC(p, n) budget_realloc(p, n)
#define STBI_FREE(p) std::free(p)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace raylane::stb {

namespace {

const stbi_uc* data(std::string_view b) {
  return reinterpret_cast<const stbi_uc*>(b.data());
}

std::string reason() {
  const char* r = stbi_failure_reason();
  return r ? std::string(r) : std::string("unknown error");
}

// Copies stb's pixels out (and frees them) if they have the size the header announced.
template <class T>
bool take(T* pixels, int w, int h, const Header& header, std::vector<T>& out, std::string& why) {
  if (!pixels) {
    why = reason();
    return false;
  }
  bool same = w == header.width && h == header.height;
  if (same) out.assign(pixels, pixels + std::size_t(w) * std::size_t(h) * 3);
  stbi_image_free(pixels);
  if (!same) why = "the image's size changed between its header and its pixels";
  return same;
}

}  // namespace

bool probe(std::string_view bytes, Header& out, std::string& why) {
  int len = int(bytes.size());
  g_budget_left = uint64_t(1) << 20;  // headers need little; an over-long chunk fails here
  if (!stbi_info_from_memory(data(bytes), len, &out.width, &out.height, &out.channels)) {
    why = reason();
    return false;
  }
  // A BMP stored top row first says so by a negative height (Microsoft's BITMAPINFOHEADER,
  // biHeight); stb_image 2.27's info call passes it on as it is, its loader takes its size.
  if (out.height < 0 && out.height != INT_MIN) out.height = -out.height;
  out.is_hdr = stbi_is_hdr_from_memory(data(bytes), len) != 0;
  out.is_16bit = stbi_is_16_bit_from_memory(data(bytes), len) != 0;
  return true;
}

bool decode(std::string_view bytes, const Header& h, uint64_t budget_bytes, Pixels& out,
            std::string& why) {
  int len = int(bytes.size()), w = 0, hh = 0, c = 0;
  if (!check_bmp_palette(bytes, why)) return false;
  g_budget_left = budget_bytes;
  bool ok = false;
  if (h.is_hdr) {
    float* p = stbi_loadf_from_memory(data(bytes), len, &w, &hh, &c, 3);
    ok = take(p, w, hh, h, out.f32, why);
  } else if (h.is_16bit) {
    stbi_us* p = stbi_load_16_from_memory(data(bytes), len, &w, &hh, &c, 3);
    ok = take(p, w, hh, h, out.u16, why);
  } else {
    stbi_uc* p = stbi_load_from_memory(data(bytes), len, &w, &hh, &c, 3);
    ok = take(p, w, hh, h, out.u8, why);
  }
  g_budget_left = 0;
  return ok;
}

}  // namespace raylane::stb
