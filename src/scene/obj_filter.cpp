#include "obj_filter.h"

#include <array>
#include <charconv>

namespace raylane {

namespace {

enum List { kPositions, kTexcoords, kNormals, kLists };

// The statement keyword of a line: its first word, after leading blanks.
std::string_view keyword_of(std::string_view line) {
  std::size_t b = line.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  std::size_t e = line.find_first_of(" \t\r", b);
  return line.substr(b, e == std::string_view::npos ? e : e - b);
}

// Which list a `v`, `vt` or `vn` line adds to; kLists for other lines.
List list_of(std::string_view keyword) {
  if (keyword == "v") return kPositions;
  if (keyword == "vt") return kTexcoords;
  if (keyword == "vn") return kNormals;
  return kLists;
}

bool is_element(std::string_view keyword) {
  return keyword == "f" || keyword == "l" || keyword == "p" || keyword == "fo";
}

// Whether index text `t` of list `k` names an element: 1..total, or -1..-(read so far).
bool index_in_range(std::string_view t, uint64_t total, uint64_t read_so_far) {
  if (t.empty()) return true;  // "1//3": no texture coordinate named
  int64_t i = 0;
  auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), i);
  if (ec != std::errc() || end != t.data() + t.size()) return true;  // Assimp's parser judges
  if (i > 0) return uint64_t(i) <= total;
  return i < 0 && uint64_t(-(i + 1)) < read_so_far;
}

// Whether every vertex of an element line (after its keyword) names elements of the lists.
bool element_in_range(std::string_view rest, const std::array<uint64_t, kLists>& total,
                      const std::array<uint64_t, kLists>& read) {
  std::size_t at = 0;
  while ((at = rest.find_first_not_of(" \t\r", at)) != std::string_view::npos) {
    std::size_t end = rest.find_first_of(" \t\r", at);
    std::string_view vertex = rest.substr(at, end == std::string_view::npos ? end : end - at);
    std::size_t part = 0;
    for (int k = 0; k < kLists && part != std::string_view::npos; ++k) {
      std::size_t slash = vertex.find('/', part);
      std::string_view index =
          vertex.substr(part, slash == std::string_view::npos ? slash : slash - part);
      if (!index_in_range(index, total[k], read[k])) return false;
      part = slash == std::string_view::npos ? slash : slash + 1;
    }
    at = end;
  }
  return true;
}

template <class Visit>
void for_each_line(std::string_view text, Visit visit) {
  for (std::size_t begin = 0, n = 1; begin < text.size(); ++n) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    visit(text.substr(begin, end - begin), begin, n);
    begin = end + 1;
  }
}

}  // namespace

ObjFiltered drop_elements_out_of_range(std::string_view obj) {
  std::array<uint64_t, kLists> total{}, read{};
  for_each_line(obj, [&](std::string_view line, std::size_t, uint64_t) {
    if (List k = list_of(keyword_of(line)); k != kLists) ++total[k];
  });
  ObjFiltered out;
  std::vector<std::pair<std::size_t, std::size_t>> blanks;  // offset, length
  for_each_line(obj, [&](std::string_view line, std::size_t offset, uint64_t n) {
    std::string_view keyword = keyword_of(line);
    if (List k = list_of(keyword); k != kLists) ++read[k];
    if (!is_element(keyword)) return;
    std::string_view rest = line.substr(line.find(keyword) + keyword.size());
    if (element_in_range(rest, total, read)) return;
    out.lines.push_back(n);
    blanks.emplace_back(offset, line.size());
  });
  if (out.lines.empty()) return out;
  out.text.assign(obj);
  for (auto [offset, length] : blanks)
    out.text.replace(offset, length, length, ' ');  // the lines keep their numbers and offsets
  return out;
}

}  // namespace raylane
