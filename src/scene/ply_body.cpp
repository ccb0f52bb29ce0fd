// The PLY body: every element's instances in header order, read through a cursor
// (ply_cursor.h); `vertex` and `face` fill a PlyMesh, any other element is read and dropped.
#include <cmath>
#include <cstdio>
#include <optional>

#include "ply_cursor.h"
#include "raylane/scene/ply.h"

namespace raylane {

namespace {

using ply_detail::AsciiCursor;
using ply_detail::BinaryCursor;

// A value read from a file as the file wrote it: integers without a fraction.
std::string number_text(double v) {
  if (v == std::floor(v) && std::abs(v) < 9.0e15) return cat(int64_t(v));
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

// Which vertex property feeds which attribute: x y z, nx ny nz, and the first texture
// coordinate pair under any of the names exporters use.
struct VertexSlots {
  static constexpr int kNone = -1;
  std::vector<int> slot;  // per property: 0–2 position, 3–5 normal, 6–7 uv, or kNone
  bool normals = false, uvs = false;

  explicit VertexSlots(const PlyElement& e) : slot(e.properties.size(), kNone) {
    static const char* const kNames[][8] = {
        {"x", "y", "z", "nx", "ny", "nz", "u", "v"},
        {"x", "y", "z", "nx", "ny", "nz", "s", "t"},
        {"x", "y", "z", "nx", "ny", "nz", "texture_u", "texture_v"},
        {"x", "y", "z", "nx", "ny", "nz", "texture_s", "texture_t"},
    };
    int found[8] = {};
    for (const auto& names : kNames)
      for (std::size_t p = 0; p < e.properties.size(); ++p)
        for (int k = 0; k < 8; ++k)
          if (!e.properties[p].is_list() && e.properties[p].name == names[k] && slot[p] == kNone &&
              !found[k]) {
            slot[p] = k, found[k] = 1;
          }
    normals = found[3] && found[4] && found[5];
    uvs = found[6] && found[7];
  }
  bool has_position() const {
    int n = 0;
    for (int s : slot)
      n += s >= 0 && s < 3;
    return n == 3;
  }
};

// Cuts a face into triangles: a triangle as it is; a quad along the diagonal whose two
// triangles face the same way (the other diagonal of a concave quad lies outside it); a polygon
// of more corners as a fan from its first corner, right for the convex polygons exporters
// write.
void triangulate(const std::vector<uint32_t>& c, const std::vector<glm::vec3>& p,
                 std::vector<std::array<uint32_t, 3>>& out) {
  if (c.size() == 4) {
    glm::dvec3 a(p[c[0]]), b(p[c[1]]), d(p[c[2]]), e(p[c[3]]);
    if (dot(cross(b - a, d - a), cross(d - a, e - a)) < 0) {
      out.push_back({c[0], c[1], c[3]});
      out.push_back({c[1], c[2], c[3]});
      return;
    }
  }
  for (std::size_t k = 1; k + 1 < c.size(); ++k)
    out.push_back({c[0], c[k], c[k + 1]});
}

template <class Cursor>
class BodyReader {
 public:
  BodyReader(Cursor& cursor, PlyMesh& mesh, const std::string& name)
      : in_(cursor), mesh_(mesh), name_(name) {}

  Result<bool> element(const PlyElement& e, bool is_vertex, bool is_face) {
    if (is_vertex) return vertices(e);
    if (is_face) return faces(e);
    for (uint64_t i = 0; i < e.count; ++i)
      for (const PlyProperty& prop : e.properties)
        if (!skip(prop)) return Error{in_.error};
    return true;
  }

 private:
  Result<bool> vertices(const PlyElement& e) {
    VertexSlots slots(e);
    if (!slots.has_position())
      return Error{cat("mesh ", quote_path(name_),
                       ": expected the PLY 'vertex' element to have properties x, y and z, "
                       "found them missing")};
    mesh_.positions.resize(e.count);
    if (slots.normals) mesh_.normals.resize(e.count);
    if (slots.uvs) mesh_.uvs.resize(e.count);
    double v[8];
    for (uint64_t i = 0; i < e.count; ++i) {
      for (std::size_t p = 0; p < e.properties.size(); ++p) {
        int s = slots.slot[p];
        if (s == VertexSlots::kNone) {
          if (!skip(e.properties[p])) return Error{in_.error};
        } else if (!in_.read(e.properties[p].type, v[s])) {
          return Error{in_.error};
        }
      }
      if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
        return Error{cat(in_.where(), ": expected finite coordinates for vertex ", i, ", found (",
                         number_text(v[0]), " ", number_text(v[1]), " ", number_text(v[2]), ")")};
      mesh_.positions[i] = glm::vec3(float(v[0]), float(v[1]), float(v[2]));
      // What is stored must be finite too: a double property's 1e300, or a float property's
      // 1e39 in an ASCII file, becomes an infinite float.
      const glm::vec3& stored = mesh_.positions[i];
      if (!std::isfinite(stored.x) || !std::isfinite(stored.y) || !std::isfinite(stored.z))
        return Error{cat(in_.where(), ": expected coordinates that fit in a float for vertex ", i,
                         ", found (", number_text(v[0]), " ", number_text(v[1]), " ",
                         number_text(v[2]), ")")};
      if (slots.normals) mesh_.normals[i] = glm::vec3(float(v[3]), float(v[4]), float(v[5]));
      if (slots.uvs) mesh_.uvs[i] = {v[6], v[7]};
    }
    return true;
  }

  Result<bool> faces(const PlyElement& e) {
    std::optional<std::size_t> list;
    for (std::size_t p = 0; p < e.properties.size(); ++p)
      if (e.properties[p].is_list() &&
          (e.properties[p].name == "vertex_indices" || e.properties[p].name == "vertex_index"))
        list = p;
    if (!list)
      return Error{cat("mesh ", quote_path(name_),
                       ": expected the PLY 'face' element to have a list property "
                       "'vertex_indices', found none")};
    mesh_.triangles.reserve(e.count);
    for (uint64_t i = 0; i < e.count; ++i)
      for (std::size_t p = 0; p < e.properties.size(); ++p) {
        if (p != *list) {
          if (!skip(e.properties[p])) return Error{in_.error};
        } else if (auto s = face(e.properties[p], i); !s) {
          return s;
        }
      }
    return true;
  }

  Result<bool> face(const PlyProperty& prop, uint64_t index) {
    uint64_t n = 0;
    if (!count(prop, n)) return Error{in_.error};
    corners_.resize(n);
    const uint64_t vertices = mesh_.positions.size();
    for (uint64_t k = 0; k < n; ++k) {
      double v = 0;
      if (!in_.read(prop.type, v)) return Error{in_.error};
      if (!(v >= 0 && v < double(vertices) && v == std::floor(v)))
        return Error{cat(in_.where(), ": expected a vertex index below ", vertices, " in face ",
                         index, ", found ", number_text(v))};
      corners_[k] = uint32_t(v);
    }
    if (n < 3) {
      ++mesh_.faces_skipped;
      return true;
    }
    triangulate(corners_, mesh_.positions, mesh_.triangles);
    return true;
  }

  // A list's count, checked against what the rest of the file can hold.
  bool count(const PlyProperty& prop, uint64_t& n) {
    double c = 0;
    if (!in_.read(prop.count_type, c)) return false;
    if (!(c >= 0) || !in_.holds(uint64_t(c), prop.type)) {
      in_.error =
          cat(in_.where(), ": expected a list length the file can hold, found ", number_text(c));
      return false;
    }
    n = uint64_t(c);
    return true;
  }

  bool skip(const PlyProperty& prop) {
    double v = 0;
    if (!prop.is_list()) return in_.read(prop.type, v);
    uint64_t n = 0;
    if (!count(prop, n)) return false;
    for (uint64_t k = 0; k < n; ++k)
      if (!in_.read(prop.type, v)) return false;
    return true;
  }

  Cursor& in_;
  PlyMesh& mesh_;
  const std::string& name_;
  std::vector<uint32_t> corners_;
};

// Every element's instances need at least one byte per property, so a header that declares
// more than its file holds is an error before anything is allocated for it.
Status check_counts(const PlyHeader& h, uint64_t body_bytes, const std::string& name) {
  uint64_t needed = 0;
  for (const PlyElement& e : h.elements) {
    uint64_t per = e.properties.empty() ? 1 : e.properties.size();
    if (e.count > body_bytes / per || needed + e.count * per > body_bytes)
      return Error{cat("mesh ", quote_path(name), ": PLY header declares ", e.count, " '", e.name,
                       "' elements, more than the file's ", body_bytes, " bytes of body hold")};
    needed += e.count * per;
  }
  return ok_status();
}

// The `vertex` element must exist, come before `face`, and be indexable by 32 bits.
Status check_vertex_element(const PlyHeader& h, const std::string& name) {
  auto named = [&](std::string_view n) {
    for (std::size_t i = 0; i < h.elements.size(); ++i)
      if (h.elements[i].name == n) return i;
    return h.elements.size();
  };
  std::size_t vertex = named("vertex"), face = named("face");
  if (vertex == h.elements.size())
    return Error{cat("mesh ", quote_path(name),
                     ": expected a PLY 'vertex' element, found none in the header")};
  if (face < vertex)
    return Error{cat("mesh ", quote_path(name),
                     ": expected the PLY 'vertex' element before 'face', found it after")};
  if (h.elements[vertex].count > UINT32_MAX)
    return Error{
        cat("mesh ", quote_path(name), ": too many vertices (", h.elements[vertex].count, ")")};
  return ok_status();
}

template <class Cursor>
Result<PlyMesh> read_elements(const PlyHeader& h, Cursor cursor, const std::string& name) {
  PlyMesh mesh;
  mesh.texture_files = h.texture_files;
  BodyReader<Cursor> reader(cursor, mesh, name);
  bool vertices_read = false, faces_read = false;
  for (const PlyElement& e : h.elements) {
    bool is_vertex = !vertices_read && e.name == "vertex";
    bool is_face = vertices_read && !faces_read && e.name == "face";
    if (auto r = reader.element(e, is_vertex, is_face); !r) return Error{r.error()};
    vertices_read |= is_vertex, faces_read |= is_face;
  }
  return mesh;
}

}  // namespace

Status check_ply_plausible(const PlyHeader& header, uint64_t file_size, const std::string& name) {
  if (Status s = check_vertex_element(header, name); !s) return s;
  uint64_t body = file_size > header.body_offset ? file_size - header.body_offset : 0;
  return check_counts(header, body, name);
}

Result<PlyMesh> read_ply(std::string_view bytes, const std::string& name) {
  auto header = read_ply_header(bytes, name);
  if (!header) return Error{header.error()};
  if (Status s = check_ply_plausible(*header, bytes.size(), name); !s) return Error{s.error()};
  std::string_view body = bytes.substr(header->body_offset);
  if (header->format == PlyFormat::kAscii)
    return read_elements(*header, AsciiCursor(body, name, header->body_line), name);
  bool big = header->format == PlyFormat::kBinaryBigEndian;
  return read_elements(*header, BinaryCursor(body, name, header->body_offset, big), name);
}

}  // namespace raylane
