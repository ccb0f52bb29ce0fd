#include "support/jpeg_writer.h"

#include <cstdio>  // jpeglib.h needs FILE and size_t declared first
#include <cstdlib>

#include <jpeglib.h>

namespace raylane::testing {

namespace {

// One DC scan of every component, then one scan per AC coefficient per component
// (ITU T.81 G.1: a progressive AC scan holds one component and any band Ss..Se).
std::vector<jpeg_scan_info> one_scan_per_coefficient(int components) {
  std::vector<jpeg_scan_info> scans;
  jpeg_scan_info dc{};
  dc.comps_in_scan = components;
  for (int c = 0; c < components; ++c)
    dc.component_index[c] = c;
  scans.push_back(dc);
  for (int c = 0; c < components; ++c)
    for (int k = 1; k < 64; ++k) {
      jpeg_scan_info ac{};
      ac.comps_in_scan = 1;
      ac.component_index[0] = c;
      ac.Ss = k, ac.Se = k;
      scans.push_back(ac);
    }
  return scans;
}

J_COLOR_SPACE colour_space(int components) {
  return components == 1 ? JCS_GRAYSCALE : components == 3 ? JCS_RGB : JCS_CMYK;
}

}  // namespace

std::string jpeg_bytes(const std::vector<uint8_t>& samples, uint32_t width, uint32_t height,
                       int components, JpegKind kind) {
  jpeg_compress_struct cinfo{};
  jpeg_error_mgr err{};
  cinfo.err = jpeg_std_error(&err);  // a test's own writer: libjpeg's exit on error is fine
  jpeg_create_compress(&cinfo);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&cinfo, &buffer, &size);
  cinfo.image_width = width, cinfo.image_height = height;
  cinfo.input_components = components;
  cinfo.in_color_space = colour_space(components);
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, 100, TRUE);
  for (int c = 0; c < cinfo.num_components; ++c)
    cinfo.comp_info[c].h_samp_factor = cinfo.comp_info[c].v_samp_factor = 1;
  std::vector<jpeg_scan_info> scans;
  if (kind == JpegKind::kProgressive) jpeg_simple_progression(&cinfo);
  if (kind == JpegKind::kManyScans) {
    scans = one_scan_per_coefficient(cinfo.num_components);
    cinfo.scan_info = scans.data();
    cinfo.num_scans = int(scans.size());
  }
  if (kind == JpegKind::kArithmetic) cinfo.arith_code = TRUE;
  jpeg_start_compress(&cinfo, TRUE);
  while (cinfo.next_scanline < height) {
    auto* row = const_cast<JSAMPLE*>(samples.data()) +
                std::size_t(cinfo.next_scanline) * width * std::size_t(components);
    jpeg_write_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_compress(&cinfo);
  jpeg_destroy_compress(&cinfo);
  std::string bytes(reinterpret_cast<const char*>(buffer), size);
  std::free(buffer);
  return bytes;
}

}  // namespace raylane::testing
