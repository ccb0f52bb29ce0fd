#include "raylane/scene/mesh_guard.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <vector>

#include "raylane/core/strings.h"

namespace raylane {

namespace {

struct PlyElement {
  std::string_view name;
  uint64_t count = 0;
  uint64_t properties = 0;
};

// Splits a header line on spaces and tabs (a CR before the newline is whitespace too).
std::vector<std::string_view> words_of(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r'))
      ++i;
    std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r')
      ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

bool is_scalar_type(std::string_view t) {
  static constexpr std::array<std::string_view, 16> kTypes = {
      "char", "uchar", "short", "ushort", "int",   "uint",   "float",   "double",
      "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
  return std::find(kTypes.begin(), kTypes.end(), t) != kTypes.end();
}

bool is_count_type(std::string_view t) {
  return is_scalar_type(t) && t != "float" && t != "double" && t != "float32" && t != "float64";
}

// One header line after `ply` and `format`; false if it breaks the PLY grammar (Paul Bourke's
// PLY description): element NAME COUNT, property TYPE NAME, property list COUNT_TYPE TYPE NAME.
// Comments, obj_info and lines of free text are skipped, as Assimp skips them: real exporters
// write such lines (Blender 2.47 wrote "Created by Blender3D 247 ..." with no `comment`) and a
// guard may refuse only what would crash or hang the reader — here, a malformed element or
// property line, or an `end_header` that is not alone on its line.
bool read_header_line(const std::vector<std::string_view>& w, std::vector<PlyElement>& elements) {
  if (w.empty()) return true;
  if (w[0] == "comment" || w[0] == "obj_info") return true;
  if (w[0] != "element" && w[0] != "property")
    return std::find(w.begin(), w.end(), "end_header") == w.end();
  if (w[0] == "element" && w.size() == 3) {
    PlyElement e;
    e.name = w[1];
    auto [p, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
    if (ec != std::errc() || p != w[2].data() + w[2].size()) return false;
    elements.push_back(e);
    return true;
  }
  if (w[0] != "property" || elements.empty()) return false;
  bool ok = (w.size() == 3 && is_scalar_type(w[1])) ||
            (w.size() == 5 && w[1] == "list" && is_count_type(w[2]) && is_scalar_type(w[3]));
  if (ok) ++elements.back().properties;
  return ok;
}

bool is_printable_text(std::string_view s) {
  return std::all_of(s.begin(), s.end(), [](char c) {
    auto u = static_cast<unsigned char>(c);
    return (u >= 0x20 && u < 0x7f) || c == '\t' || c == '\r';
  });
}

// Reads the header up to a line that is exactly `end_header`. Anything outside the grammar is
// rejected here, because Assimp 5.2's PLY reader crashes on malformed headers (found by
// fuzz_mesh: a binary PLY with `end_header` inside an element line).
Status read_ply_header(std::string_view head, std::vector<PlyElement>& elements,
                       uint64_t& header_bytes, const std::string& name) {
  auto bad = [&](int line, std::string_view what) {
    return Error{cat("mesh ", quote_path(name), ": PLY header line ", line, ": ", what)};
  };
  std::size_t pos = 0;
  for (int number = 1;; ++number) {
    std::size_t eol = head.find('\n', pos);
    if (eol == std::string_view::npos)
      return Error{cat("mesh ", quote_path(name), ": PLY header has no end_header line")};
    std::string_view line = head.substr(pos, eol - pos);
    pos = eol + 1;
    if (!is_printable_text(line)) return bad(number, "holds bytes that are not text");
    auto w = words_of(line);
    if (number == 1) {
      if (w.size() != 1 || w[0] != "ply") return bad(number, "expected 'ply'");
    } else if (number == 2) {
      bool known =
          w.size() == 3 && w[0] == "format" && w[2] == "1.0" &&
          (w[1] == "ascii" || w[1] == "binary_little_endian" || w[1] == "binary_big_endian");
      if (!known)
        return bad(number,
                   "expected 'format ascii|binary_little_endian|"
                   "binary_big_endian 1.0'");
    } else if (w.size() == 1 && w[0] == "end_header") {
      header_bytes = pos;
      return ok_status();
    } else if (!read_header_line(w, elements)) {
      return bad(number, cat("expected an element or property line of the PLY grammar, found ",
                             in_quotes(line)));
    }
  }
}

// Assimp 5.2 sizes its face data from the `vertex` element: a PLY whose vertices are named
// otherwise, or declared after the faces, made it request 22.9 GB for a 297-byte file
// (found by fuzz_mesh). raylane needs vertices anyway, so both are errors here.
Status check_vertex_element(const std::vector<PlyElement>& elements, const std::string& name) {
  auto is = [](std::string_view n) { return [n](const PlyElement& e) { return e.name == n; }; };
  auto vertex = std::find_if(elements.begin(), elements.end(), is("vertex"));
  if (vertex == elements.end())
    return Error{cat("mesh ", quote_path(name),
                     ": expected a PLY 'vertex' element, found none in the header")};
  if (std::find_if(elements.begin(), vertex, is("face")) != vertex)
    return Error{cat("mesh ", quote_path(name),
                     ": expected the PLY 'vertex' element before 'face', found it after")};
  return ok_status();
}

char lower(char c) {
  return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c;
}

bool starts_with_ignoring_case(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (lower(s[i]) != prefix[i]) return false;
  return true;
}

// Assimp picks its PLY reader by the extension or by a case-insensitive "ply" in the first
// bytes, so both send a file through the strict check (found by fuzz_mesh: a header starting
// `Ply` slipped past a case-sensitive test and hung Assimp's reader).
bool may_be_read_as_ply(std::string_view head, const std::string& name) {
  std::string_view n = name;
  return starts_with_ignoring_case(head, "ply") ||
         (n.size() >= 4 && starts_with_ignoring_case(n.substr(n.size() - 4), ".ply"));
}

}  // namespace

Status check_mesh_plausible(std::string_view head, uint64_t file_size, const std::string& name) {
  if (file_size > kMaxMeshFileBytes) return Error{cat("mesh ", quote_path(name), " is over 4 GiB")};
  if (!may_be_read_as_ply(head, name)) return ok_status();
  std::vector<PlyElement> elements;
  uint64_t header_bytes = 0;
  if (Status s = read_ply_header(head, elements, header_bytes, name); !s) return s;
  if (Status s = check_vertex_element(elements, name); !s) return s;
  uint64_t body = file_size > header_bytes ? file_size - header_bytes : 0;
  uint64_t needed = 0;
  for (const PlyElement& e : elements) {
    uint64_t per = e.properties == 0 ? 1 : e.properties;
    if (e.count > body / per || needed + e.count * per > body)
      return Error{cat("mesh ", quote_path(name),
                       ": PLY header declares more elements than the file holds")};
    needed += e.count * per;
  }
  return ok_status();
}

}  // namespace raylane
