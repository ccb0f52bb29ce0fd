// What a render's film and images take, known from the screen and the options before anything
// is allocated: a render that cannot have it is refused up front (issue 34), never ended by
// std::bad_alloc hours in or at the first pixel.
#include "raylane/core/memory.h"
#include "raylane/core/strings.h"
#include "render_request.h"

namespace raylane::cli {

namespace {

// The bytes of the film and of every image made from it, per pixel:
// - path: the film's sums (3 + AOV channels doubles); its copy in a checkpoint or --resume file
//   being written or read, or the whole film assembled on rank 0 under mpirun; the colour image
//   and one per AOV (3 floats), the AOVs again as EXR layers, and the writer's encoded copy;
// - ray casting: the image, its viewable copy (depth and ids mapped) and the writer's copy.
uint64_t bytes_per_pixel(const RenderRequest& r, bool distributed) {
  constexpr uint64_t kImage = 3 * sizeof(float);
  if (!r.path) return 3 * kImage;
  const AovSet& aovs = r.path_settings.aovs;
  uint64_t film = uint64_t(3 + aovs.channels()) * sizeof(double);
  bool film_copied = distributed || r.checkpoints.checkpoint || r.checkpoints.resume;
  uint64_t aov_images = r.aov_outputs.size() + (aovs.empty() ? 0 : 1);
  return film * (film_copied ? 2 : 1) + kImage * (2 + aov_images) +
         uint64_t(aovs.channels()) * sizeof(float);
}

}  // namespace

Status render_fits_in_memory(const RenderRequest& r, const Scene& scene, bool distributed) {
  // A --region's film, AOVs and images hold the region's pixels alone.
  const auto& region = r.path_settings.region;
  const uint32_t width = region ? region->width() : scene.width;
  const uint32_t height = region ? region->height() : scene.height;
  uint64_t bytes = uint64_t(width) * height * bytes_per_pixel(r, distributed);
  std::string size =
      region ? cat(width, "x", height, " region of the ", scene.width, "x", scene.height, " screen")
             : cat(width, "x", height);
  std::string what = r.path ? cat("a ", size, " render (its film",
                                  r.path_settings.aovs.empty() ? "" : ", AOVs", " and images)")
                            : cat("the ", size, " image");
  return check_memory(bytes, what);
}

}  // namespace raylane::cli
