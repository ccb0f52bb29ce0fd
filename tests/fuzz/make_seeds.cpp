// Writes the small seed inputs of the RGBE and mesh fuzzers into OUTDIR/rgbe and OUTDIR/mesh
// (generated, so no binaries are committed), plus the PLY files named after OUTDIR (the
// course's letters). Mesh seeds start with the fuzzer's format byte (0: PLY, 1: OBJ).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "raylane/image/rgbe.h"

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

void mesh_seeds(const fs::path& dir) {
  put(dir / "ascii.ply", std::string(1, '\0') + kPlyAscii);
  put(dir / "binary.ply", std::string(1, '\0') + ply_binary());
  put(dir / "square.obj", std::string(1, '\1') + kObj);
}

void copy_ply_seed(const fs::path& from, const fs::path& dir) {
  std::ifstream in(from, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  put(dir / from.filename(), std::string(1, '\0') + bytes.str());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: make_seeds OUTDIR [PLY...]\n");
    return 2;
  }
  fs::path out(argv[1]);
  fs::create_directories(out / "rgbe");
  fs::create_directories(out / "mesh");
  rgbe_seeds(out / "rgbe");
  mesh_seeds(out / "mesh");
  for (int i = 2; i < argc; ++i)
    copy_ply_seed(argv[i], out / "mesh");
  return 0;
}
