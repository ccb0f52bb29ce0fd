// What a render's film and images take, known from the screen and the options before anything
// is allocated: a render that cannot have it is refused up front, never ended by
// std::bad_alloc hours in or at the first pixel.
#include <omp.h>
#include <sys/resource.h>

#include <algorithm>

#include "raylane/core/memory.h"
#include "raylane/core/strings.h"
#include "render_request.h"

namespace raylane::cli {

namespace {

// The bytes per pixel of the film and of what writing its files holds beside it, measured
// with /usr/bin/time -v on 2048x2048 renders (docs/design.md, "Memory"):
// - path: the film's sums (3 + AOV channels doubles), twice under mpirun (rank 0 assembles a
//   copy); while the files are written (one at a time, write_film_outputs), the colour image,
//   the larger of one AOV's image and an EXR's AOV layers, and the encoder's copy of every
//   channel (OpenEXR's half or float rows; 8-bit PNG and RGBE take less). Checkpoints and
//   --resume stream the sums, with no copy. The measured and the counted bytes stand side by
//   side in docs/design.md, "Memory".
// - ray casting: the image, its viewable copy (depth and ids mapped) and the writer's copy.
uint64_t bytes_per_pixel(const RenderRequest& r, bool distributed) {
  constexpr uint64_t kImage = 3 * sizeof(float);
  if (!r.path) return 3 * kImage;
  const uint64_t channels = uint64_t(r.path_settings.aovs.channels());
  const uint64_t film = (3 + channels) * sizeof(double) * (distributed ? 2 : 1);
  const uint64_t one_aov_or_layers = std::max(kImage, channels * sizeof(float));
  const uint64_t encoder = (3 + channels) * sizeof(float);
  return film + kImage + one_aov_or_layers + encoder;
}

// Address space each rendering thread beyond the first reserves: its stack (RLIMIT_STACK's
// size, which libgomp's threads take by default) and the heap glibc's malloc reserves for it
// (an arena of HEAP_MAX_SIZE, 64 MiB on 64-bit systems: glibc malloc/arena.c). Under
// `ulimit -v` those reservations count as much as the film; without them a render could pass
// the check and run out of address space while writing.
uint64_t thread_reserve(int threads) {
  constexpr uint64_t kArena = uint64_t(64) << 20, kDefaultStack = uint64_t(8) << 20;
  rlimit stack{};
  uint64_t stack_bytes = kDefaultStack;
  if (getrlimit(RLIMIT_STACK, &stack) == 0 && stack.rlim_cur != RLIM_INFINITY)
    stack_bytes = std::min<uint64_t>(stack.rlim_cur, uint64_t(1) << 30);
  return uint64_t(std::max(threads - 1, 0)) * (kArena + stack_bytes);
}

}  // namespace

Status render_fits_in_memory(const RenderRequest& r, const Scene& scene, bool distributed) {
  // A --region's film, AOVs and images hold the region's pixels alone.
  const auto& region = r.path_settings.region;
  const uint32_t width = region ? region->width() : scene.width;
  const uint32_t height = region ? region->height() : scene.height;
  const int threads = r.threads > 0 ? r.threads : omp_get_max_threads();
  uint64_t bytes =
      uint64_t(width) * height * bytes_per_pixel(r, distributed) + thread_reserve(threads);
  std::string size =
      region ? cat(width, "x", height, " region of the ", scene.width, "x", scene.height, " screen")
             : cat(width, "x", height);
  const std::string with_threads = threads > 1 ? cat(", with ", threads, " threads") : "";
  std::string what =
      r.path ? cat("a ", size, " render (its film", r.path_settings.aovs.empty() ? "" : ", AOVs",
                   " and images", with_threads, ")")
             : cat("the ", size, " image", threads > 1 ? cat(" (", threads, " threads)") : "");
  return check_memory(bytes, what);
}

}  // namespace raylane::cli
