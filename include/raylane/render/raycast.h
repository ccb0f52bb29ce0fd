// Ray-casting views: one ray per pixel centre, shaded by a mode (the course's first project).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "raylane/core/enum_names.h"
#include "raylane/image/image.h"
#include "raylane/render/camera/camera.h"
#include "raylane/render/film/region.h"
#include "raylane/scene/scene.h"
#include "raylane/trace/tracer.h"

namespace raylane {

enum class RaycastMode {
  kNormal,    // (N + 1) / 2 of the shading normal
  kDepth,     // the hit distance t in every channel; 0 for a miss
  kAlbedo,    // Kd, times the material's texture at the hit
  kId,        // (kind tag + 1, row index, 0); 0 for a miss
  kLit,       // ambient·Kd plus a Phong term from each emitting sphere's centre, shadowed
  kUv,        // (u, v, 0) of the hit's texture coordinates (prims/<kind>.h, texcoord_ref)
  kPosition,  // the hit point
};

inline constexpr EnumNames<RaycastMode, 7> kRaycastModeNames{
    {"normal", "depth", "albedo", "id", "lit", "uv", "position"}};
inline std::optional<RaycastMode> raycast_mode_from_name(std::string_view name) {
  return kRaycastModeNames.from_name(name);
}
inline std::string_view raycast_mode_name(RaycastMode mode) {
  return kRaycastModeNames.name(mode);
}

struct RaycastStats {
  uint64_t camera_rays = 0;
  uint64_t shadow_rays = 0;
};

// Renders every pixel; camera rays go out in 4×4-pixel tiles (coherent packets), rows are
// stored top row first (Image's convention). With a region, only the bands of rows that meet it
// are traced (each whole, so its packets and pixels are those of a whole render), and the image
// is the region's alone.
Image render_raycast(const Tracer& tracer, RaycastMode mode, RaycastStats* stats = nullptr,
                     const std::optional<PixelRegion>& region = std::nullopt);

// The image of a view as a person can look at it in an 8-bit file: `depth` normalised to the
// image's range of hit distances (nearest 1, farthest 0.1, misses 0), `id` as a distinct
// colour per primitive (misses black); other modes unchanged. HDR and PFM files keep the raw
// values, which this does not.
Image viewable(const Image& raw, RaycastMode mode);

}  // namespace raylane
