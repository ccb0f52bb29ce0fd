#include "raylane/trace/ray_set_io.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "raylane/core/atomic_file.h"
#include "raylane/core/input_file.h"
#include "raylane/core/strings.h"

namespace raylane {

namespace {

constexpr char kRaysMagic[8] = {'R', 'A', 'Y', 'S', 'E', 'T', '1', '\0'};
constexpr char kTrisMagic[8] = {'T', 'R', 'I', 'S', 'O', 'U', 'P', '1'};
constexpr char kHitsMagic[8] = {'H', 'I', 'T', 'S', '0', '0', '1', '\0'};
constexpr std::size_t kRaysHeader = 32, kTrisHeader = 16, kHitsHeader = 16;
constexpr std::size_t kRayRecord = 32, kTriRecord = 36, kHitRecord = 8;

static_assert(std::endian::native == std::endian::little, "the files are little endian");

// A whole file whose header is `magic` and whose records fill the rest exactly; the count
// is checked against the file's size before anything is allocated for it.
struct Contents {
  std::string bytes;
  uint32_t count = 0;
};

Result<Contents> read_records(const std::string& path, const char (&magic)[8], std::size_t header,
                              std::size_t record, const char* what) {
  auto file_size = regular_file_size(path);
  if (!file_size) return Error{cat(path, ": cannot read: ", file_size.error())};
  uint64_t size = *file_size;
  if (size < header)
    return Error{cat(path, ": expected a ", header, "-byte header, found ", size, " bytes")};
  std::ifstream in(path, std::ios::binary);
  Contents c;
  c.bytes.resize(header);
  if (!in.read(c.bytes.data(), std::streamsize(header))) return Error{cat(path, ": read failed")};
  if (std::memcmp(c.bytes.data(), magic, 8) != 0)
    return Error{cat(path, ": expected the magic ", in_quotes(std::string(magic, 7)), " of a ",
                     what, " file, found ", in_quotes(c.bytes.substr(0, 7)))};
  std::memcpy(&c.count, c.bytes.data() + 8, 4);
  uint64_t want = header + uint64_t(c.count) * record;
  if (c.count > kMaxRaySetRecords)
    return Error{cat(path, ": ", c.count, " records is more than the limit ", kMaxRaySetRecords)};
  if (size != want)
    return Error{cat(path, ": the header announces ", c.count, " records (", want,
                     " bytes), the file has ", size, " bytes")};
  c.bytes.resize(want);
  if (!in.read(c.bytes.data() + header, std::streamsize(want - header)))
    return Error{cat(path, ": read failed")};
  return c;
}

uint32_t u32_at(const std::string& b, std::size_t at) {
  uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

void put(std::string& out, const void* p, std::size_t n) {
  out.append(static_cast<const char*>(p), n);
}

std::string header(const char (&magic)[8], std::initializer_list<uint32_t> words,
                   std::size_t size) {
  std::string out(magic, 8);
  for (uint32_t w : words)
    put(out, &w, 4);
  out.resize(size, '\0');
  return out;
}

// One record: a finite origin, a finite unit direction, t bounds that are numbers.
Status check_ray(const float (&v)[8]) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(v[k]))
      return Error{cat("expected a finite origin, found (", v[0], " ", v[1], " ", v[2], ")")};
  double len = std::sqrt(double(v[3]) * v[3] + double(v[4]) * v[4] + double(v[5]) * v[5]);
  if (!(std::abs(len - 1) <= kUnitDirectionTolerance))
    return Error{cat("expected a unit direction (length 1 ± ", kUnitDirectionTolerance,
                     "), found (", v[3], " ", v[4], " ", v[5], ") of length ", len)};
  if (std::isnan(v[6]) || std::isnan(v[7]))
    return Error{cat("expected t bounds that are numbers, found ", v[6], " and ", v[7])};
  return ok_status();
}

}  // namespace

Result<RaySetFile> read_ray_set(const std::string& path) {
  auto c = read_records(path, kRaysMagic, kRaysHeader, kRayRecord, "ray-set");
  if (!c) return Error{c.error()};
  RaySetFile set;
  set.flags = u32_at(c->bytes, 12);
  set.width = u32_at(c->bytes, 16);
  set.height = u32_at(c->bytes, 20);
  set.rays.resize(c->count);
  for (uint32_t i = 0; i < c->count; ++i) {
    float v[8];
    std::memcpy(v, c->bytes.data() + kRaysHeader + std::size_t(i) * kRayRecord, kRayRecord);
    if (Status s = check_ray(v); !s) return Error{cat(path, ": ray ", i, ": ", s.error())};
    set.rays.set(i, Rayf{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6], v[7]});
  }
  return set;
}

Status write_ray_set(const std::string& path, const RaySetFile& set) {
  std::string out = header(
      kRaysMagic, {uint32_t(set.rays.size()), set.flags, set.width, set.height}, kRaysHeader);
  for (std::size_t i = 0; i < set.rays.size(); ++i) {
    Rayf r = set.rays.get(i);
    float v[8] = {r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.tmin, r.tmax};
    put(out, v, kRayRecord);
  }
  return write_file_atomically(path, out);
}

Result<uint32_t> read_triangle_soup(const std::string& path, uint32_t material,
                                    TriangleTable& table) {
  auto c = read_records(path, kTrisMagic, kTrisHeader, kTriRecord, "triangle-soup");
  if (!c) return Error{c.error()};
  TriangleTable soup;
  table_reserve(soup, c->count);
  for (uint32_t i = 0; i < c->count; ++i) {
    float v[9];
    std::memcpy(v, c->bytes.data() + kTrisHeader + std::size_t(i) * kTriRecord, kTriRecord);
    for (float x : v)
      if (!std::isfinite(x))
        return Error{cat(path, ": triangle ", i, ": expected finite coordinates, found ", x)};
    glm::vec3 p0(v[0], v[1], v[2]), p1(v[3], v[4], v[5]), p2(v[6], v[7], v[8]);
    glm::dvec3 n = cross(glm::dvec3(p1) - glm::dvec3(p0), glm::dvec3(p2) - glm::dvec3(p0));
    double len = length(n);
    glm::vec3 nf = len > 0 && std::isfinite(len) ? glm::vec3(n / len) : glm::vec3(0, 0, 1);
    soup.append({p0, p1, p2}, {nf, nf, nf}, material);
  }
  std::apply(
      [&](auto&... dst) {
        std::apply([&](auto&... src) { (dst.insert(dst.end(), src.begin(), src.end()), ...); },
                   soup.columns());
      },
      table.columns());
  return c->count;
}

Status write_triangle_soup(const std::string& path, const TriangleTable& table) {
  std::string out = header(kTrisMagic, {uint32_t(table.size())}, kTrisHeader);
  for (uint32_t i = 0; i < table.size(); ++i)
    for (glm::vec3 p : {table.p0(i), table.p1(i), table.p2(i)})
      put(out, &p.x, 4), put(out, &p.y, 4), put(out, &p.z, 4);
  return write_file_atomically(path, out);
}

Result<std::vector<HitRecord>> read_hits(const std::string& path, uint32_t* flags) {
  auto c = read_records(path, kHitsMagic, kHitsHeader, kHitRecord, "hits");
  if (!c) return Error{c.error()};
  if (flags) *flags = u32_at(c->bytes, 12);
  std::vector<HitRecord> hits(c->count);
  std::memcpy(hits.data(), c->bytes.data() + kHitsHeader, std::size_t(c->count) * kHitRecord);
  return hits;
}

Status write_hits(const std::string& path, const std::vector<HitRecord>& hits, uint32_t flags) {
  static_assert(sizeof(HitRecord) == kHitRecord);
  std::string out = header(kHitsMagic, {uint32_t(hits.size()), flags}, kHitsHeader);
  put(out, hits.data(), hits.size() * kHitRecord);
  return write_file_atomically(path, out);
}

}  // namespace raylane
