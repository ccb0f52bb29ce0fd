#include "raylane/scene/mesh_guard.h"

#include <charconv>
#include <sstream>

#include "raylane/core/strings.h"

namespace raylane {

namespace {

struct PlyElement {
  uint64_t count = 0;
  uint64_t properties = 0;
};

// Reads "element NAME COUNT" and "property ..." lines up to end_header.
bool read_ply_header(std::string_view head, std::vector<PlyElement>& elements,
                     uint64_t& header_bytes) {
  std::size_t end = head.find("end_header");
  if (end == std::string_view::npos) return false;
  std::size_t eol = head.find('\n', end);
  header_bytes = eol == std::string_view::npos ? head.size() : eol + 1;
  std::istringstream in{std::string(head.substr(0, end))};
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword, name, count;
    words >> keyword;
    if (keyword == "element") {
      words >> name >> count;
      PlyElement e;
      auto [p, ec] = std::from_chars(count.data(), count.data() + count.size(), e.count);
      if (ec != std::errc()) e.count = UINT64_MAX;  // unreadable or too large: implausible
      (void)p;
      elements.push_back(e);
    } else if (keyword == "property" && !elements.empty()) {
      ++elements.back().properties;
    }
  }
  return true;
}

}  // namespace

Status check_mesh_plausible(std::string_view head, uint64_t file_size, const std::string& name) {
  if (file_size > kMaxMeshFileBytes) return Error{cat("mesh ", in_quotes(name), " is over 4 GiB")};
  if (head.substr(0, 3) != "ply") return ok_status();
  std::vector<PlyElement> elements;
  uint64_t header_bytes = 0;
  if (!read_ply_header(head, elements, header_bytes))
    return Error{cat("mesh ", in_quotes(name), ": PLY header has no end_header")};
  uint64_t body = file_size > header_bytes ? file_size - header_bytes : 0;
  uint64_t needed = 0;
  for (const PlyElement& e : elements) {
    uint64_t per = e.properties == 0 ? 1 : e.properties;
    if (e.count > body / per || needed + e.count * per > body)
      return Error{
          cat("mesh ", in_quotes(name), ": PLY header declares more elements than the file holds")};
    needed += e.count * per;
  }
  return ok_status();
}

}  // namespace raylane
