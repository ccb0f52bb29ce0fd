#include "ply_export.h"

#include <cstring>

#include "raylane/core/atomic_file.h"
#include "raylane/core/strings.h"

namespace raylane::bench {

namespace {

template <class T>
void append_le(std::string& out, T v) {  // x86-64 is little-endian, as the header says
  char bytes[sizeof(T)];
  std::memcpy(bytes, &v, sizeof(T));
  out.append(bytes, sizeof(T));
}

}  // namespace

// Format: Paul Bourke's PLY description (binary_little_endian 1.0).
Status write_ply_soup(const std::string& path, const TriangleTable& t) {
  std::string out = cat("ply\nformat binary_little_endian 1.0\ncomment raylane benchmark mesh\n",
                        "element vertex ", 3 * t.size(),
                        "\nproperty float x\nproperty float y\nproperty float z\n", "element face ",
                        t.size(), "\nproperty list uchar int vertex_indices\nend_header\n");
  out.reserve(out.size() + t.size() * (36 + 13));
  for (uint32_t i = 0; i < t.size(); ++i)
    for (const glm::vec3& p : {t.p0(i), t.p1(i), t.p2(i)})
      append_le(out, p.x), append_le(out, p.y), append_le(out, p.z);
  for (uint32_t i = 0; i < t.size(); ++i) {
    append_le(out, uint8_t(3));
    for (int32_t k = 0; k < 3; ++k)
      append_le(out, int32_t(3 * i) + k);
  }
  return write_file_atomically(path, out);
}

}  // namespace raylane::bench
