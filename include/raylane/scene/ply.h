// raylane's own PLY reader (ASCII and binary of either byte order), so that PLY files — the
// format of scanned models and of the benchmark's generated meshes — never reach Assimp, whose
// PLY reader hangs, over-allocates, aborts and leaks on damaged files (found by fuzz_mesh).
// The grammar is Greg Turk's PLY as Paul Bourke describes it: a text header of `element NAME
// COUNT` lines, each followed by its `property TYPE NAME` or `property list COUNT_TYPE TYPE
// NAME` lines, then a body holding each element's instances in header order.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/core/vec_math.h"
#include "raylane/prims/surface.h"

namespace raylane {

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

// The eight scalar types, by their size and kind; `int8`…`float64` are the same types.
enum class PlyType : uint8_t {
  kNone,
  kInt8,
  kUint8,
  kInt16,
  kUint16,
  kInt32,
  kUint32,
  kFloat32,
  kFloat64
};

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kNone;        // the value's type (a list's item type)
  PlyType count_type = PlyType::kNone;  // a list's count type; kNone for a scalar property
  bool is_list() const { return count_type != PlyType::kNone; }
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  std::vector<std::string> texture_files;  // `comment TextureFile NAME` lines, as written
  uint64_t body_offset = 0;                // the byte after `end_header`'s line
  int body_line = 1;                       // the line number the body starts on
};

// Whether a file is PLY: its name ends in .ply, or it starts with "ply" in any case (Assimp
// picks its PLY reader on either, so both must come here).
bool is_ply(std::string_view head, std::string_view name);

// The longest PLY header raylane reads: 16 MiB, past any comment block a tool writes (a
// header is read to its end, not to a buffer's size), yet bounded, so a file of text that
// never says end_header is refused after reading 16 MiB of it.
inline constexpr uint64_t kMaxPlyHeaderBytes = uint64_t(16) << 20;

// The header, if `bytes` start with one that follows the grammar exactly; errors name the
// header line ("PLY header line 3: expected …, found …"). `bytes` must hold the whole header or
// kMaxPlyHeaderBytes of it.
Result<PlyHeader> read_ply_header(std::string_view bytes, const std::string& name);

// Whether the header's `vertex` element exists, comes before `face` and is indexable by 32
// bits, and whether the file is long enough for what the header declares (every property of
// every element takes at least one byte).
Status check_ply_plausible(const PlyHeader& header, uint64_t file_size, const std::string& name);

// What raylane takes from a PLY file: vertex positions, and normals and texture coordinates
// when every vertex has them, and the faces cut into triangles.
struct PlyMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty, or one per vertex (nx ny nz)
  std::vector<TexCoord> uvs;       // empty, or one per vertex (u v, s t, texture_u …)
  std::vector<std::array<uint32_t, 3>> triangles;
  uint64_t faces_skipped = 0;  // faces of fewer than three corners
  std::vector<std::string> texture_files;
};

// Reads a whole PLY file held in memory. Errors say where: "NAME:LINE:COL: …" in an ASCII
// body, "NAME: byte N: …" in a binary one. Every allocation is bounded by the file's size.
Result<PlyMesh> read_ply(std::string_view bytes, const std::string& name);

}  // namespace raylane
