// OpenEXR files (image/exr.h): float and half round trips, metadata and layers read back,
// what OpenEXR's own exrheader sees, and damaged or hostile files refused without a crash or a
// large allocation. Files the writer cannot make (Y only, tiled, integer, subsampled) are made
// with OpenEXR's C++ library directly.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "raylane/core/alloc_budget.h"
#include "raylane/image/exr.h"
#include "raylane/image/input_image.h"
#include "raylane/image/write_image.h"
#include "support/paths.h"

namespace raylane {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void spit(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Every channel value different, so that a swapped channel, row or column shows.
Image ramp(uint32_t w, uint32_t h) {
  Image img(w, h);
  for (std::size_t i = 0; i < img.rgb.size(); ++i)
    img.rgb[i] = 0.001f * float(i) + 0.25f * float(i % 3);
  return img;
}

ExrWriteOptions as_half() {
  ExrWriteOptions o;
  o.half = true;
  return o;
}

ExrWriteOptions with_metadata(std::vector<std::string> lines) {
  ExrWriteOptions o;
  o.metadata = std::move(lines);
  return o;
}

std::string exr_bytes(const Image& img, const std::vector<ExrLayer>& layers = {},
                      const ExrWriteOptions& options = {}) {
  std::string path = testing::temp_dir() + "/t.exr";
  std::FILE* f = std::fopen(path.c_str(), "wb");
  Status s = write_exr(f, img, layers, options);
  std::fclose(f);
  EXPECT_TRUE(s.ok()) << s.error();
  return slurp(path);
}

TEST(Exr, FloatRoundTripIsExact) {
  Image img = ramp(37, 21);  // 21 rows: two ZIP blocks of 16 lines, the second partial
  img.set(3, 4, glm::vec3(1e-30f, 3.4e38f, 0.1f));
  auto back = decode_exr(exr_bytes(img));
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->width, 37u);
  EXPECT_EQ(back->height, 21u);
  EXPECT_EQ(back->rgb, img.rgb);
}

TEST(Exr, HalfRoundTripIsWithinHalfPrecision) {
  Image img(64, 9);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> log10(-6, 5);  // subnormal halves to past the largest
  for (float& v : img.rgb)
    v = std::pow(10.0f, log10(rng));
  auto back = decode_exr(exr_bytes(img, {}, as_half()));
  ASSERT_TRUE(back.ok()) << back.error();
  ASSERT_EQ(back->rgb.size(), img.rgb.size());
  for (std::size_t i = 0; i < img.rgb.size(); ++i) {
    float want = std::min(img.rgb[i], 65504.0f);  // beyond half's range: its largest value
    if (want >= 6.1035156e-05f)                   // normal halves: 11 significant bits
      EXPECT_LE(std::abs(back->rgb[i] - want), want * 0x1p-11f) << i << " " << img.rgb[i];
    else  // subnormal halves: an absolute step of 2^-24
      EXPECT_LE(std::abs(back->rgb[i] - want), 0x1p-25f) << i << " " << img.rgb[i];
  }
  // Half files are smaller: the writer did store halves.
  EXPECT_LT(exr_bytes(img, {}, as_half()).size(), exr_bytes(img).size());
}

TEST(Exr, MetadataComesBackAsStringAttributes) {
  Image img = ramp(4, 3);
  auto info = probe_exr(exr_bytes(img, {}, with_metadata({"RAYLANE_SPP=64", "NOTE=a=b c"})));
  ASSERT_TRUE(info.ok()) << info.error();
  auto has = [&](const std::string& line) {
    return std::find(info->metadata.begin(), info->metadata.end(), line) != info->metadata.end();
  };
  EXPECT_TRUE(has("RAYLANE_SPP=64"));
  EXPECT_TRUE(has("NOTE=a=b c"));
  EXPECT_TRUE(has("software=raylane " RAYLANE_VERSION));
}

TEST(Exr, BadMetadataIsRefused) {
  Image img = ramp(2, 2);
  std::FILE* f = std::tmpfile();
  EXPECT_FALSE(write_exr(f, img, {}, with_metadata({"no equals sign"})).ok());
  EXPECT_FALSE(write_exr(f, img, {}, with_metadata({"=value"})).ok());
  auto s = write_exr(f, img, {}, with_metadata({"dataWindow=0 0 1 1"}));
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find("dataWindow"), std::string::npos) << s.error();
  std::fclose(f);
}

std::vector<ExrLayer> aov_layers(uint32_t w, uint32_t h) {
  std::size_t n = std::size_t(w) * h;
  ExrLayer albedo{"albedo", {"R", "G", "B"}, std::vector<float>(n * 3)};
  ExrLayer normal{"normal", {"X", "Y", "Z"}, std::vector<float>(n * 3)};
  ExrLayer depth{"depth", {"Z"}, std::vector<float>(n)};
  for (std::size_t i = 0; i < n * 3; ++i) {
    albedo.data[i] = 0.5f + 0.001f * float(i);
    normal.data[i] = -1.0f + 0.002f * float(i);  // negatives kept: normals point anywhere
  }
  for (std::size_t i = 0; i < n; ++i)
    depth.data[i] = 10.0f + float(i);
  return {albedo, normal, depth};
}

TEST(Exr, LayersAreNamedAndReadBack) {
  Image img = ramp(5, 17);
  auto layers = aov_layers(5, 17);
  std::string bytes = exr_bytes(img, layers);
  auto info = probe_exr(bytes);
  ASSERT_TRUE(info.ok()) << info.error();
  EXPECT_EQ(info->layers, (std::vector<std::string>{"", "albedo", "depth", "normal"}));
  EXPECT_EQ(info->channels,
            (std::vector<std::string>{"B", "G", "R", "albedo.B", "albedo.G", "albedo.R", "depth.Z",
                                      "normal.X", "normal.Y", "normal.Z"}));
  for (const ExrLayer& want : layers) {
    auto got = decode_exr_layer(bytes, want.name);
    ASSERT_TRUE(got.ok()) << got.error();
    // The file keeps channels in alphabetical order; read back, each one must match its own.
    ASSERT_EQ(got->data.size(), want.data.size());
    const std::size_t n = want.channels.size();
    for (std::size_t k = 0; k < n; ++k) {
      auto it = std::find(got->channels.begin(), got->channels.end(), want.channels[k]);
      ASSERT_NE(it, got->channels.end()) << want.name << "." << want.channels[k];
      std::size_t j = std::size_t(it - got->channels.begin());
      for (std::size_t p = 0; p < want.data.size() / n; ++p)
        ASSERT_EQ(got->data[p * n + j], want.data[p * n + k]) << want.name << " pixel " << p;
    }
  }
  auto rgb = decode_exr(bytes);
  ASSERT_TRUE(rgb.ok()) << rgb.error();
  EXPECT_EQ(rgb->rgb, img.rgb);  // the layers do not disturb the picture
  EXPECT_FALSE(decode_exr_layer(bytes, "nope").ok());
}

// The fuzzer's half seed: OpenEXRCore 3.1.5 crashed reading its layer alone while the RGB
// channels were skipped by a null pointer (src/image/exr.cpp, point_channels).
TEST(Exr, HalfLayersAreReadBack) {
  for (uint32_t h : {3u, 17u, 40u}) {
    for (bool depth_alone : {true, false}) {  // depth alone: the seed's case, the last channel
      auto layers = aov_layers(5, h);
      if (depth_alone) layers = {layers[2]};
      std::string bytes = exr_bytes(ramp(5, h), layers, as_half());
      for (const ExrLayer& want : layers) {
        auto got = decode_exr_layer(bytes, want.name);
        ASSERT_TRUE(got.ok()) << got.error();
        ASSERT_EQ(got->data.size(), want.data.size());
        const std::size_t n = want.channels.size();
        for (std::size_t p = 0; p < want.data.size() / n; ++p)
          for (std::size_t k = 0; k < n; ++k) {
            // Alphabetical in the file: X Y Z and Z stay in order, R G B comes back B G R.
            std::size_t j = want.name == "albedo" ? n - 1 - k : k;
            float v = want.data[p * n + k];
            ASSERT_NEAR(got->data[p * n + j], v, std::abs(v) * 0x1p-11f + 0x1p-24f)
                << want.name << " pixel " << p << " channel " << k;
          }
      }
    }
  }
}

TEST(Exr, BadLayersAreRefused) {
  Image img = ramp(2, 2);
  std::FILE* f = std::tmpfile();
  ExrLayer short_data{"a", {"R"}, std::vector<float>(3)};
  ExrLayer unnamed{"", {"R"}, std::vector<float>(4)};
  ExrLayer twice{"a", {"R", "R"}, std::vector<float>(8)};
  ExrLayer dotted_channel{"a", {"R.x"}, std::vector<float>(4)};
  for (const ExrLayer& bad : {short_data, unnamed, twice, dotted_channel})
    EXPECT_FALSE(write_exr(f, img, {bad}).ok()) << bad.name;
  // A nested layer ("diffuse.direct") has dots between non-empty parts only.
  for (const char* name : {".a", "a.", "a..b", "."})
    EXPECT_FALSE(write_exr(f, img, {{name, {"R"}, std::vector<float>(4)}}).ok()) << name;
  EXPECT_TRUE(write_exr(f, img, {{"a.b", {"R"}, std::vector<float>(4)}}).ok());
  std::fclose(f);
}

// exrheader (Debian's openexr package) lists what OpenEXR itself sees in a written file.
TEST(Exr, ExrheaderListsTheChannels) {
  if (std::system("command -v exrheader >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "exrheader is not installed (Debian package openexr)";
  std::string path = testing::temp_dir() + "/aov.exr";
  WriteOptions opts;
  opts.exr_half = true;
  opts.exr_layers = aov_layers(3, 2);
  opts.metadata = {"RAYLANE_SPP=16"};
  ASSERT_TRUE(write_image(path, ramp(3, 2), opts).ok());
  std::FILE* p = ::popen(("exrheader '" + path + "' 2>&1").c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;)
    out.append(buf, n);
  EXPECT_EQ(::pclose(p), 0) << out;
  for (const char* want :
       {"R, 16-bit floating-point", "G, 16-bit floating-point", "B, 16-bit floating-point",
        "albedo.R, 16-bit", "normal.Z, 16-bit", "depth.Z, 16-bit", "zip, multi-scanline blocks",
        "RAYLANE_SPP (type string): \"16\"", "dataWindow (type box2i): (0 0) - (2 1)"})
    EXPECT_NE(out.find(want), std::string::npos) << want << "\n" << out;
}

TEST(Exr, WriteImageAndReadImageGoByTheExtension) {
  std::string dir = testing::temp_dir();
  Image img = ramp(6, 4);
  ASSERT_TRUE(write_image(dir + "/a.EXR", img).ok());
  auto back = read_image(dir + "/a.EXR");
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->rgb, img.rgb);
  EXPECT_EQ(*format_from_path("x.exr"), ImageFormat::kExr);
  // Atomic as the other formats: nothing but the file is left in the folder.
  std::size_t files = 0;
  for ([[maybe_unused]] auto& e : std::filesystem::directory_iterator(dir))
    ++files;
  EXPECT_EQ(files, 1u);
}

TEST(Exr, TexturesReadExrAndRefuseBadValues) {
  Image img = ramp(4, 4);
  std::string bytes = exr_bytes(img);
  auto info = probe_input_image(bytes, "t.exr");
  ASSERT_TRUE(info.ok()) << info.error();
  EXPECT_EQ(info->format, InputFormat::kExr);
  EXPECT_TRUE(info->is_float);
  auto tex = decode_input_image(bytes, "t.exr");
  ASSERT_TRUE(tex.ok()) << tex.error();
  EXPECT_EQ(tex->rgb, img.rgb);
  for (float bad : {-1.0f, std::nanf(""), INFINITY}) {
    Image b = img;
    b.set(2, 1, glm::vec3(0.5f, bad, 0.5f));
    auto r = decode_input_image(exr_bytes(b), "t.exr");
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_NE(r.error().find("pixel (2, 1)"), std::string::npos) << r.error();
  }
  // read_image (diff, convert) keeps them, as it does for PFM: diff counts them.
  Image n = img;
  n.set(0, 0, glm::vec3(-2, 0, 0));
  auto raw = decode_exr(exr_bytes(n));
  ASSERT_TRUE(raw.ok());
  EXPECT_EQ(raw->rgb[0], -2.0f);
}

// ---- Files raylane does not write, made with OpenEXR's C++ library.

std::string write_with_imf(const std::string& name, const Imf::Header& header,
                           const Imf::FrameBuffer& fb, int height) {
  std::string path = testing::temp_dir() + "/" + name;
  {
    Imf::OutputFile out(path.c_str(), header);
    out.setFrameBuffer(fb);
    out.writePixels(height);
  }
  return slurp(path);
}

TEST(Exr, GreyFilesBecomeRgb) {
  std::vector<float> y = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};
  Imf::Header h(3, 2);
  h.channels().insert("Y", Imf::Channel(Imf::FLOAT));
  Imf::FrameBuffer fb;
  fb.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(y.data()), 4, 12));
  auto img = decode_exr(write_with_imf("y.exr", h, fb, 2));
  ASSERT_TRUE(img.ok()) << img.error();
  for (uint32_t i = 0; i < 6; ++i)
    EXPECT_EQ(img->at(i % 3, i / 3), glm::vec3(y[i], y[i], y[i])) << i;
}

TEST(Exr, AnOffsetDataWindowIsReadFromItsTopRow) {
  Image img = ramp(4, 3);
  const Imath::Box2i window({-10, 100}, {-7, 102});  // x −10…−7, y 100…102
  Imf::Header h(window, window);
  Imf::FrameBuffer fb;
  // The frame buffer is addressed by window coordinates: base = &pixel(0,0) − (x0, y0).
  char* base = reinterpret_cast<char*>(img.rgb.data()) - (-10 * 12) - (100 * 4 * 12);
  for (int k = 0; k < 3; ++k) {
    std::string c(1, "RGB"[k]);
    h.channels().insert(c, Imf::Channel(Imf::FLOAT));
    fb.insert(c, Imf::Slice(Imf::FLOAT, base + 4 * k, 12, 4 * 12));
  }
  auto back = decode_exr(write_with_imf("offset.exr", h, fb, 3));
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->rgb, img.rgb);
}

TEST(Exr, UnsupportedKindsAreClearErrors) {
  std::vector<float> px(16 * 16 * 3, 1.0f);
  std::vector<uint32_t> ids(16 * 16, 7);
  auto rgb_fb = [&](Imf::Header& h, Imf::FrameBuffer& fb) {
    for (int k = 0; k < 3; ++k) {
      std::string c(1, "RGB"[k]);
      h.channels().insert(c, Imf::Channel(Imf::FLOAT));
      fb.insert(c, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data() + k), 12, 16 * 12));
    }
  };
  {  // tiled
    Imf::Header h(16, 16);
    h.setTileDescription(Imf::TileDescription(8, 8));
    Imf::FrameBuffer fb;
    rgb_fb(h, fb);
    std::string path = testing::temp_dir() + "/tiled.exr";
    {
      Imf::TiledOutputFile out(path.c_str(), h);
      out.setFrameBuffer(fb);
      out.writeTiles(0, 1, 0, 1);
    }
    auto r = decode_exr(slurp(path));
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().find("tiled"), std::string::npos) << r.error();
  }
  {  // integer R, G, B
    Imf::Header h(16, 16);
    Imf::FrameBuffer fb;
    for (const char* c : {"R", "G", "B"}) {
      h.channels().insert(c, Imf::Channel(Imf::UINT));
      fb.insert(c, Imf::Slice(Imf::UINT, reinterpret_cast<char*>(ids.data()), 4, 64));
    }
    auto r = decode_exr(write_with_imf("uint.exr", h, fb, 16));
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().find("integers"), std::string::npos) << r.error();
  }
  {  // R and G without B: not a colour image (and no Y to fall back on)
    Imf::Header h(16, 16);
    Imf::FrameBuffer fb;
    for (const char* c : {"R", "G"}) {
      h.channels().insert(c, Imf::Channel(Imf::FLOAT));
      fb.insert(c, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data()), 12, 16 * 12));
    }
    auto r = decode_exr(write_with_imf("rg.exr", h, fb, 16));
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().find("no R, G, B or Y"), std::string::npos) << r.error();
  }
  {  // no colour channel at all
    Imf::Header h(16, 16);
    Imf::FrameBuffer fb;
    h.channels().insert("id", Imf::Channel(Imf::UINT));
    fb.insert("id", Imf::Slice(Imf::UINT, reinterpret_cast<char*>(ids.data()), 4, 64));
    std::string bytes = write_with_imf("id.exr", h, fb, 16);
    auto r = decode_exr(bytes);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().find("no R, G, B or Y"), std::string::npos) << r.error();
    EXPECT_FALSE(probe_input_image(bytes, "id.exr").ok());
  }
}

// ---- Damaged and hostile files.

// The byte offset of the first value of attribute `name` in an EXR header.
std::size_t attribute_value(const std::string& bytes, const std::string& name,
                            const std::string& type) {
  std::string key = name + '\0' + type + '\0';
  std::size_t at = bytes.find(key);
  EXPECT_NE(at, std::string::npos) << name;
  return at + key.size() + 4;  // past the 4-byte size
}

void put_le32(std::string& bytes, std::size_t at, int32_t v) {
  std::memcpy(&bytes[at], &v, 4);  // EXR is little endian, as is every machine raylane runs on
}

TEST(Exr, EveryTruncationIsAnError) {
  std::string bytes = exr_bytes(ramp(9, 40), aov_layers(9, 40));
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    auto r = decode_exr(std::string_view(bytes).substr(0, n));
    EXPECT_FALSE(r.ok()) << "cut at " << n;
  }
}

TEST(Exr, DamagedBytesGiveAnErrorOrAnImageNeverACrash) {
  std::string good = exr_bytes(ramp(9, 40), aov_layers(9, 40));
  std::mt19937 rng(3);
  int errors = 0;
  for (std::size_t i = 0; i < good.size(); ++i) {
    std::string bad = good;
    bad[i] = char(bad[i] ^ (1 + rng() % 255));
    auto r = decode_exr(bad);
    if (!r.ok()) {
      ++errors;
      continue;
    }
    ASSERT_EQ(r->rgb.size(), std::size_t(r->width) * r->height * 3);
    ASSERT_LE(uint64_t(r->width) * r->height, kMaxImagePixels);
  }
  EXPECT_GT(errors, 0);
}

TEST(Exr, AHugeDataWindowIsRefusedBeforeAllocating) {
  std::string bytes = exr_bytes(ramp(4, 4));
  std::size_t dw = attribute_value(bytes, "dataWindow", "box2i");
  // Beyond the pixel limit: 65536 × 65536.
  std::string huge = bytes;
  put_le32(huge, dw + 8, 65535);
  put_le32(huge, dw + 12, 65535);
  // Within the pixel limit (16384 × 16384 = 2^28) but not within what ~400 bytes can hold.
  std::string big = bytes;
  put_le32(big, dw + 8, 16383);
  put_le32(big, dw + 12, 16383);
  // Inverted: max below min.
  std::string empty = bytes;
  put_le32(empty, dw + 8, -5);
  // One PIZ chunk of 2^24 × 16 pixels: the chunk table fits, and PIZ has no tight bound.
  std::string wide = bytes;
  put_le32(wide, dw + 8, (1 << 24) - 1);
  put_le32(wide, dw + 12, 15);
  wide[attribute_value(bytes, "compression", "compression")] = 4;  // PIZ_COMPRESSION
  for (const std::string* b : {&huge, &big, &empty, &wide}) {
    AllocBudget budget(uint64_t(16) << 20);  // the pixels of `big` alone would be 3 GiB
    auto r = decode_exr(*b);
    ASSERT_FALSE(r.ok());
    EXPECT_FALSE(budget.exceeded()) << r.error();
    EXPECT_LT(budget.peak(), uint64_t(1) << 20) << r.error();
    auto t = decode_input_image(*b, "t.exr");
    EXPECT_FALSE(t.ok());
  }
  auto r = decode_exr(big);
  EXPECT_NE(r.error().find("more than"), std::string::npos) << r.error();
  r = decode_exr(huge);
  EXPECT_NE(r.error().find("limit"), std::string::npos) << r.error();
}

TEST(Exr, ReadImageNamesTheFile) {
  std::string path = testing::temp_dir() + "/broken.exr";
  spit(path, exr_bytes(ramp(4, 4)).substr(0, 100));
  auto r = read_image(path);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("cannot read '" + path + "': "), std::string::npos) << r.error();
  auto t = read_input_image(path);
  ASSERT_FALSE(t.ok());
  EXPECT_EQ(t.error().rfind(path, 0), 0u) << t.error();
}

}  // namespace
}  // namespace raylane
