// Writes the small seed inputs of the RGBE, mesh and image fuzzers into OUTDIR/rgbe, OUTDIR/mesh
// and OUTDIR/image (generated, so no binaries are committed), plus copies of the files named
// after OUTDIR: PLY files (the course's letters) as mesh seeds, any other file (an image of
// Debian's assimp-testmodels, if installed) as an image seed. Mesh seeds start with the fuzzer's
// format byte (0: PLY, 1: OBJ), image seeds with the name byte (1: a .tga name).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "raylane/image/exr.h"
#include "raylane/image/pfm.h"
#include "raylane/image/rgbe.h"
#include "support/hostile_files.h"
#include "support/jpeg_writer.h"

namespace {

namespace fs = std::filesystem;

void put(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

raylane::Image gradient(uint32_t w, uint32_t h) {
  raylane::Image image(w, h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)  // runs (flat rows) and literals (ramps) for the RLE coder
      image.set(x, y, {float(x / 4), float(y) * 0.5f, x % 3 == 0 ? 1e-3f : 40.0f});
  return image;
}

void rgbe_seeds(const fs::path& dir) {
  put(dir / "flat.hdr", raylane::encode_rgbe(gradient(4, 3)));  // too narrow for RLE
  put(dir / "rle.hdr", raylane::encode_rgbe(gradient(16, 4), {"EXPOSURE=1"}));
  put(dir / "one.hdr", raylane::encode_rgbe(gradient(1, 1)));
}

const char* kPlyAscii =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";

std::string ply_binary() {
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  s.append(reinterpret_cast<const char*>(v), sizeof v);
  const unsigned char n = 3;
  const int idx[3] = {0, 1, 2};
  s.push_back(char(n));
  s.append(reinterpret_cast<const char*>(idx), sizeof idx);
  return s;
}

const char* kObj =
    "# a square and a triangle with normals\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vn 0 0 1\nf 1//1 2//1 3//1 4//1\nf -1 -2 -3\n";

// What raylane's PLY reader reads beyond positions: normals, texture coordinates, a texture
// comment, an element it skips, a list with another count type, a quad.
const char* kPlyRich =
    "ply\nformat ascii 1.0\ncomment TextureFile t.png\nelement vertex 4\nproperty double x\n"
    "property float y\nproperty int16 z\nproperty float nx\nproperty float ny\n"
    "property float nz\nproperty float s\nproperty float t\nelement edge 1\n"
    "property list uint8 int32 ends\nelement face 1\nproperty uchar flags\n"
    "property list ushort uint vertex_indices\nend_header\n0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n"
    "1 1 0 0 0 1 1 1\n0 1 0 0 0 1 0 1\n2 0 1\n7 4 0 1 2 3\n";

void mesh_seeds(const fs::path& dir) {
  put(dir / "rich.ply", std::string(1, '\0') + kPlyRich);
  put(dir / "ascii.ply", std::string(1, '\0') + kPlyAscii);
  put(dir / "binary.ply", std::string(1, '\0') + ply_binary());
  put(dir / "square.obj", std::string(1, '\1') + kObj);
  // Faces naming a vertex, texture coordinate or normal the file lacks: dropped, not refused.
  put(dir / "missing_elements.obj",
      std::string(1, '\1') + kObj + "vt 0 0\nf 1 2 9\nf -9 1 2\nf 1/3 2/1 3/1\nf 1//4 2//1 3//1\n");
  // A header longer than the first 64 KiB raylane once read of a mesh (docs/scene-language.md,
  // "Limits").
  put(dir / "long_header.ply",
      std::string(1, '\0') + raylane::testing::ply_with_long_header(70000));
}

// A TGA (type 2: uncompressed true colour, 24 bits, bottom-up) and a BMP (24 bits, bottom-up,
// rows padded to 4 bytes) of a 2×2 image, after the formats' published header layouts.
std::string tga_2x2() {
  std::string s(18, '\0');
  s[2] = 2, s[12] = 2, s[14] = 2, s[16] = 24;
  for (int i = 0; i < 4; ++i)
    s += std::string{char(40 * i), char(200 - 40 * i), char(90)};
  return s;
}

std::string le32(uint32_t v) {
  return {char(v), char(v >> 8), char(v >> 16), char(v >> 24)};
}

std::string bmp_2x2() {
  std::string pixels;
  for (int row = 0; row < 2; ++row)
    pixels +=
        std::string{char(10 * row), char(250), char(60), char(0), char(120), char(30), '\0', '\0'};
  std::string s = "BM" + le32(54 + uint32_t(pixels.size())) + le32(0) + le32(54);
  s += le32(40) + le32(2) + le32(2) + std::string{1, 0, 24, 0} + le32(0) +
       le32(uint32_t(pixels.size())) + le32(2835) + le32(2835) + le32(0) + le32(0);
  return s + pixels;
}

// An EXR as raylane writes it (ZIP), float or half, with a layer beside RGB.
std::string exr_seed(bool half) {
  raylane::Image image = gradient(5, 3);
  raylane::ExrLayer depth{"depth", {"Z"}, std::vector<float>(15, 2.5f)};
  raylane::ExrWriteOptions options;
  options.half = half;
  options.metadata = {"RAYLANE_SPP=4"};
  std::FILE* f = std::tmpfile();
  if (!f || !raylane::write_exr(f, image, {depth}, options)) return "";
  std::string bytes(std::size_t(std::ftell(f)), '\0');
  std::rewind(f);
  bytes.resize(std::fread(bytes.data(), 1, bytes.size(), f));
  std::fclose(f);
  return bytes;
}

void image_seeds(const fs::path& dir) {
  put(dir / "rle.hdr", std::string(1, '\0') + raylane::encode_rgbe(gradient(16, 4)));
  put(dir / "flat.pfm", std::string(1, '\0') + raylane::encode_pfm(gradient(3, 2)));
  put(dir / "small.tga", std::string(1, '\1') + tga_2x2());
  put(dir / "small.bmp", std::string(1, '\0') + bmp_2x2());
  put(dir / "float.exr", std::string(1, '\0') + exr_seed(false));
  put(dir / "half.exr", std::string(1, '\0') + exr_seed(true));
  // Hostile images (docs/design.md, "Images in"): a PNG bomb (4096² 1-bit pixels in 13 KB, past the
  // image memory budget once decoded) and a luminance-chroma EXR (Y full, RY and BY subsampled).
  put(dir / "bomb.png", std::string(1, '\0') + raylane::testing::png_zero_bomb(4096, 4096));
  put(dir / "yc.exr",
      std::string(1, '\0') + raylane::testing::exr_luminance_chroma(8, 6, [](int x, int y) {
        return glm::vec3(x * 0.1f, y * 0.2f, 0.3f);
      }));
  // Small JPEGs of each coding raylane reads (the models' photos are large and baseline).
  using raylane::testing::JpegKind;
  std::vector<uint8_t> rgb(16 * 8 * 3), grey(16 * 8);
  for (std::size_t i = 0; i < rgb.size(); ++i)
    rgb[i] = uint8_t(i * 37 % 251);
  for (std::size_t i = 0; i < grey.size(); ++i)
    grey[i] = uint8_t(i * 11);
  using raylane::testing::jpeg_bytes;
  put(dir / "baseline.jpg", std::string(1, '\0') + jpeg_bytes(rgb, 16, 8, 3));
  put(dir / "progressive.jpg",
      std::string(1, '\0') + jpeg_bytes(rgb, 16, 8, 3, JpegKind::kProgressive));
  put(dir / "grey.jpg", std::string(1, '\0') + jpeg_bytes(grey, 16, 8, 1));
}

void copy_seed(const fs::path& from, const fs::path& dir, char prefix) {
  std::ifstream in(from, std::ios::binary);
  if (!in) return;  // an optional seed that is not installed here
  std::ostringstream bytes;
  bytes << in.rdbuf();
  put(dir / from.filename(), std::string(1, prefix) + bytes.str());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: make_seeds OUTDIR [PLY or image...]\n");
    return 2;
  }
  fs::path out(argv[1]);
  fs::create_directories(out / "rgbe");
  fs::create_directories(out / "mesh");
  fs::create_directories(out / "image");
  rgbe_seeds(out / "rgbe");
  mesh_seeds(out / "mesh");
  image_seeds(out / "image");
  for (int i = 2; i < argc; ++i) {
    fs::path p(argv[i]);
    if (p.extension() == ".ply")
      copy_seed(p, out / "mesh", '\0');
    else
      copy_seed(p, out / "image", p.extension() == ".tga" ? '\1' : '\0');
  }
  return 0;
}
