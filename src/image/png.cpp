#include "raylane/image/png.h"

#include <png.h>

#include <cmath>
#include <csetjmp>
#include <vector>

namespace raylane {

uint8_t srgb_encode_8bit(float linear) {
  float v = linear > 0 ? std::min(linear, 1.0f) : 0.0f;  // NaN → 0
  // IEC 61966-2-1: linear below 0.0031308, else 1.055·v^(1/2.4) − 0.055.
  float s = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(s * 255.0f));
}

namespace {

// The row buffer lives outside the setjmp frame, so longjmp leaves nothing half-destroyed.
Status write_rows(png_structp png, png_infop info, std::FILE* f, const Image& image,
                  std::vector<uint8_t>& row, double exposure) {
  if (setjmp(png_jmpbuf(png))) return Error{"libpng failed to write the image"};
  png_init_io(png, f);
  png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  const float gain = float(std::exp2(exposure));
  for (uint32_t y = 0; y < image.height; ++y) {
    for (std::size_t k = 0; k < std::size_t(image.width) * 3; ++k)
      row[k] = srgb_encode_8bit(image.rgb[image.index(0, y) + k] * gain);
    png_write_row(png, row.data());
  }
  png_write_end(png, nullptr);
  return ok_status();
}

}  // namespace

Status write_png(std::FILE* f, const Image& image, double exposure) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) return Error{"libpng: out of memory"};
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return Error{"libpng: out of memory"};
  }
  std::vector<uint8_t> row(std::size_t(image.width) * 3);
  Status s = write_rows(png, info, f, image, row, exposure);
  png_destroy_write_struct(&png, &info);
  return s;
}

}  // namespace raylane
