// The ray-set exchange files of docs/ray-sets.md: `.rays` (a ray set), `.tris` (a triangle
// soup) and `.hits` (the answers), all little endian, so raylane and any other tracer can be
// compared on identical rays. Readers check every size against the file before allocating
// and report `file: what was expected, what was found`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/prims/triangle.h"
#include "raylane/trace/ray_stream.h"

namespace raylane {

inline constexpr uint32_t kRaySetOcclusionFlag = 1;  // flags bit 0: any hit suffices
inline constexpr uint64_t kMaxRaySetRecords = uint64_t(1) << 28;
// A ray's direction must be unit length to within this (docs/ray-sets.md): a direction
// normalised in float or double and stored as float is within 1e-6 of it.
inline constexpr double kUnitDirectionTolerance = 1e-3;

struct RaySetFile {
  RayStream rays;
  uint32_t flags = 0;
  uint32_t width = 0, height = 0;  // a camera-ray set's image size, else 0
  bool occlusion() const { return flags & kRaySetOcclusionFlag; }
};

// One answer: closest hit: t and the triangle's index in the soup (t = +inf and prim =
// 0xffffffff for a miss); occlusion: t = 0, prim = 0 if occluded, 0xffffffff if not.
struct HitRecord {
  float t;
  uint32_t prim;
};
inline constexpr uint32_t kNoHit = 0xffffffffu;

Result<RaySetFile> read_ray_set(const std::string& path);
Status write_ray_set(const std::string& path, const RaySetFile& set);

// Appends the soup's triangles in file order (flat: vertex normals are the face normal) to
// `table` with `material`; returns how many. Non-finite vertices are an error.
Result<uint32_t> read_triangle_soup(const std::string& path, uint32_t material,
                                    TriangleTable& table);
Status write_triangle_soup(const std::string& path, const TriangleTable& table);

Result<std::vector<HitRecord>> read_hits(const std::string& path, uint32_t* flags = nullptr);
Status write_hits(const std::string& path, const std::vector<HitRecord>& hits, uint32_t flags);

}  // namespace raylane
