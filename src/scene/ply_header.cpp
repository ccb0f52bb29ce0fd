// The PLY header grammar (include/raylane/scene/ply.h). It is strict about element and
// property lines, because a reader that trusts a malformed one reads the body wrongly, and
// lenient about lines of free text, which real exporters write (Blender 2.47 wrote "Created by
// Blender3D 247 ..." without `comment`).
#include <algorithm>
#include <array>
#include <charconv>
#include <utility>

#include "raylane/core/strings.h"
#include "raylane/scene/ply.h"

namespace raylane {

namespace {

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

PlyType type_named(std::string_view t) {
  static constexpr std::array<std::pair<std::string_view, PlyType>, 16> kTypes = {{
      {"char", PlyType::kInt8},
      {"int8", PlyType::kInt8},
      {"uchar", PlyType::kUint8},
      {"uint8", PlyType::kUint8},
      {"short", PlyType::kInt16},
      {"int16", PlyType::kInt16},
      {"ushort", PlyType::kUint16},
      {"uint16", PlyType::kUint16},
      {"int", PlyType::kInt32},
      {"int32", PlyType::kInt32},
      {"uint", PlyType::kUint32},
      {"uint32", PlyType::kUint32},
      {"float", PlyType::kFloat32},
      {"float32", PlyType::kFloat32},
      {"double", PlyType::kFloat64},
      {"float64", PlyType::kFloat64},
  }};
  for (const auto& [name, type] : kTypes)
    if (name == t) return type;
  return PlyType::kNone;
}

bool is_integer(PlyType t) {
  return t != PlyType::kNone && t != PlyType::kFloat32 && t != PlyType::kFloat64;
}

// One `element` or `property` line; false if it breaks the grammar.
bool read_declaration(const std::vector<std::string_view>& w, std::vector<PlyElement>& elements) {
  if (w[0] == "element") {
    if (w.size() != 3) return false;
    PlyElement e;
    e.name = std::string(w[1]);
    auto [p, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
    if (ec != std::errc() || p != w[2].data() + w[2].size()) return false;
    elements.push_back(std::move(e));
    return true;
  }
  if (elements.empty()) return false;  // a property before any element
  PlyProperty prop;
  if (w.size() == 3) {
    prop.type = type_named(w[1]);
    prop.name = std::string(w[2]);
  } else if (w.size() == 5 && w[1] == "list") {
    prop.count_type = type_named(w[2]);
    prop.type = type_named(w[3]);
    prop.name = std::string(w[4]);
    if (!is_integer(prop.count_type)) return false;
  } else {
    return false;
  }
  if (prop.type == PlyType::kNone) return false;
  elements.back().properties.push_back(std::move(prop));
  return true;
}

bool is_printable_text(std::string_view s) {
  return std::all_of(s.begin(), s.end(), [](char c) {
    auto u = static_cast<unsigned char>(c);
    return (u >= 0x20 && u < 0x7f) || c == '\t' || c == '\r';
  });
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

Result<PlyFormat> format_of(const std::vector<std::string_view>& w) {
  if (w.size() == 3 && w[0] == "format" && w[2] == "1.0") {
    if (w[1] == "ascii") return PlyFormat::kAscii;
    if (w[1] == "binary_little_endian") return PlyFormat::kBinaryLittleEndian;
    if (w[1] == "binary_big_endian") return PlyFormat::kBinaryBigEndian;
  }
  return Error{"expected 'format ascii|binary_little_endian|binary_big_endian 1.0'"};
}

// A line after `format`: a declaration, a comment (kept if it names a texture file, as
// photogrammetry tools write `comment TextureFile NAME`), or free text without `end_header`.
bool read_line_after_format(const std::vector<std::string_view>& w, std::string_view line,
                            PlyHeader& header) {
  if (w.empty() || w[0] == "obj_info") return true;
  if (w[0] == "comment") {
    if (w.size() >= 3 && w[1] == "TextureFile") {
      std::size_t at = line.find("TextureFile") + 11;
      std::string_view rest = line.substr(at);
      std::size_t first = rest.find_first_not_of(" \t"), last = rest.find_last_not_of(" \t\r");
      header.texture_files.emplace_back(rest.substr(first, last - first + 1));
    }
    return true;
  }
  if (w[0] == "element" || w[0] == "property") return read_declaration(w, header.elements);
  return std::find(w.begin(), w.end(), "end_header") == w.end();
}

}  // namespace

bool is_ply(std::string_view head, std::string_view name) {
  return starts_with_ignoring_case(head, "ply") ||
         (name.size() >= 4 && starts_with_ignoring_case(name.substr(name.size() - 4), ".ply"));
}

Result<PlyHeader> read_ply_header(std::string_view bytes, const std::string& name) {
  auto bad = [&](int line, std::string_view what) {
    return Error{cat("mesh ", quote_path(name), ": PLY header line ", line, ": ", what)};
  };
  PlyHeader header;
  std::size_t pos = 0;
  for (int number = 1;; ++number) {
    std::size_t eol = bytes.find('\n', pos);
    if (eol != std::string_view::npos && eol >= kMaxPlyHeaderBytes)
      return Error{cat("mesh ", quote_path(name), ": PLY header is longer than 16 MiB (",
                       kMaxPlyHeaderBytes, " bytes), the limit")};
    if (eol == std::string_view::npos)
      return Error{
          cat("mesh ", quote_path(name),
              bytes.size() >= kMaxPlyHeaderBytes
                  ? ": PLY header is longer than 16 MiB (the limit) or has no end_header line"
                  : ": PLY header has no end_header line")};
    std::string_view line = bytes.substr(pos, eol - pos);
    pos = eol + 1;
    if (!is_printable_text(line)) return bad(number, "holds bytes that are not text");
    auto w = words_of(line);
    if (number == 1) {
      if (w.size() != 1 || w[0] != "ply") return bad(number, "expected 'ply'");
    } else if (number == 2) {
      auto format = format_of(w);
      if (!format) return bad(number, format.error());
      header.format = *format;
    } else if (w.size() == 1 && w[0] == "end_header") {
      header.body_offset = pos;
      header.body_line = number + 1;
      return header;
    } else if (!read_line_after_format(w, line, header)) {
      return bad(number, cat("expected an element or property line of the PLY grammar, found ",
                             in_quotes(line)));
    }
  }
}

}  // namespace raylane
