// `raylane render --stats-json FILE`: the end-of-render summary and the phases of `--stats` as
// one JSON object, for scripts (tools/converge reads it instead of the summary line's text).
#pragma once

#include <string>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/render/path.h"
#include "render_request.h"

namespace raylane::cli {

// What the summary line and --stats print, as plain values.
struct RenderSummary {
  uint32_t width = 0, height = 0;  // the screen's
  std::string region;              // --region as a JSON array [x0, y0, x1, y1]; empty: none
  std::string mode;                // "path" or a ray-casting view
  std::string integrator, sampler, shading;  // path only
  int spp = 0;
  bool interrupted = false;
  double seconds = 0;         // the render's wall time (no loading, no BVH)
  PathStats stats;            // rays by kind (a view: camera and shadow rays)
  bool phases_timed = false;  // stats.phases holds the phases
  std::string tracer, isa;
  int threads = 0, processes = 1;  // threads per process
  std::size_t bvh_nodes = 0;
  double bvh_seconds = 0;
  double wait_seconds = 0, busy_seconds = 0;  // under mpirun, summed over the processes
  int tiles_moved = 0, balances = 0;
  std::vector<std::string> outputs;  // the images written
  bool path = false;                 // a path render: the series is listed (maybe empty)
  std::vector<SeriesSave> series;    // --save-at's images, in pass order
};

// The summary as one JSON object (its keys: the README, `--stats-json`).
std::string summary_json(const RenderSummary& s);
// Writes it to `path` atomically; prints why on failure.
bool write_summary_json(const std::string& path, const RenderSummary& s);

// The summary of a finished render: its request, the scene's size, the BVH, the path
// tracer's (or a view's) counts, an MPI job's balance and --save-at series (`run`), the wall
// time and the images written.
RenderSummary render_summary(const RenderRequest& r, const Scene& scene, const Bvh& bvh,
                             const PathStats& stats, const PathOutcome& run, double seconds,
                             bool interrupted, int processes, std::vector<std::string> written);

}  // namespace raylane::cli
