// What `raylane render` was asked to do, once its options are read (render_command.cpp).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "args.h"
#include "checkpoint.h"
#include "cluster.h"
#include "raylane/core/enum_names.h"
#include "raylane/core/memory.h"
#include "raylane/core/strings.h"
#include "raylane/image/exr.h"
#include "raylane/image/write_image.h"
#include "raylane/render/film/aov.h"
#include "raylane/render/path.h"
#include "raylane/render/raycast.h"
#include "raylane/simd/isa.h"
#include "raylane/trace/tracer.h"

namespace raylane::cli {

// When the processes of an MPI job deal their tiles again by measured cost (docs/cluster.md,
// "Balance"): never (round-robin throughout), when it pays, or at every check (for tests).
enum class TileBalance { kOff, kAuto, kAlways };
inline constexpr EnumNames<TileBalance, 3> kTileBalanceNames{{"off", "auto", "always"}};

struct RenderRequest {
  std::optional<std::string> scene_path;
  std::vector<std::string> outputs;
  bool path = true;  // --mode path (the default); otherwise a ray-casting mode
  RaycastMode mode = RaycastMode::kLit;
  PathSettings path_settings;
  CheckpointOptions checkpoints;
  TracerBackend tracer = TracerBackend::kPacket;
  Isa isa = best_isa();
  double exposure = 0;
  int threads = 0;
  bool also_png = false, lenient = false, quiet = false;
  bool no_checkpoint = false;          // --no-checkpoint: a --resume film is not saved again
  std::vector<std::string> overrides;  // --set lines
  uint64_t image_memory = default_image_memory();        // --image-memory, in bytes
  bool image_memory_chosen = false;                      // --image-memory given
  std::vector<std::pair<std::string, Aov>> aov_outputs;  // --aov: sibling PFM files
  bool exr_half = false;
  bool spp_given = false;
  std::vector<int> save_at;  // --save-at: passes after which the image is written too, sorted
  TileBalance balance = TileBalance::kAuto;  // --balance
  bool print_phases = false;                 // --stats
  std::optional<std::string> stats_json;     // --stats-json FILE
  std::vector<std::string> warnings;         // about the options, printed unless --quiet
};

// The header lines (HDR, EXR) of a path-traced image after RAYLANE_MODE and RAYLANE_SPP: the
// settings a re-render or a --resume must match. `raylane render` and view's S write the same.
inline std::vector<std::string> path_metadata(const PathSettings& p) {
  return {cat("RAYLANE_SEED=", p.seed), cat("RAYLANE_INTEGRATOR=", integrator_name(p.integrator)),
          cat("RAYLANE_SAMPLER=", sampler_name(p.sampler))};
}

constexpr int kExitInterrupted = 130;  // 128 + SIGINT, as shells report it
constexpr int kMaxSpp = 1 << 24;

// One save of the --save-at series: the pass count, the render's cost up to that pass (the
// writing of earlier saves left out, so a render stopped at `spp` would have cost about the
// same) and the files written (rescue files where they replaced an output).
struct SeriesSave {
  int spp = 0;
  double seconds = 0;      // wall time since the render started
  double cpu_seconds = 0;  // this process's CPU time (all threads) since it started
  std::vector<std::string> outputs;
};

// A path render's results on rank 0 (other ranks hold their own share's only).
struct PathOutcome {
  Film film;  // the whole render's sums on rank 0: the files are written from it
  PathStats stats;
  int status = 0;            // kExitUsage when the film to resume cannot be used
  bool interrupted = false;  // Ctrl-C on any process stopped it
  // An MPI job's balance, summed over its processes (printed by --stats).
  double wait_seconds = 0;     // waiting in the agreement after each pass for the slowest process
  double busy_seconds = 0;     // rendering passes
  int tiles_moved = 0;         // tiles dealt to another process, over all the times
  int balances = 0;            // times the tiles were dealt again (--balance)
  bool series_failed = false;  // a --save-at image went to a rescue file or nowhere
  std::vector<SeriesSave> series;  // the --save-at images written, in pass order (rank 0)
};

// Renders the path-traced image: progress, --time, Ctrl-C and checkpoints, with the tiles
// shared between the cluster's processes (render_path_run.cpp).
PathOutcome run_path(const RenderRequest& r, const Tracer& tracer, const Cluster& cluster);

// An error naming the bytes the film and the images of this render need, unless this process
// can have them (render_memory.cpp); checked before anything is rendered.
Status render_fits_in_memory(const RenderRequest& r, const Scene& scene, bool distributed);

// Writes one output of a render, or (the folder removed, the disk full) a rescue file instead
// (image/write_fallback.h); prints the path written on stdout and any failure on stderr.
// Returns the path written, or nothing; `failed` becomes true unless `out` itself was written
// (pass_series.cpp).
std::optional<std::string> write_render_output(const std::string& out, const Image& image,
                                               const WriteOptions& options, bool& failed);

// Every file write_render_output wrote in this process, in order: what an out-of-memory
// failure that still escapes names as written (main.cpp).
const std::vector<std::string>& files_written();

// --stats under mpirun: how long the processes waited for the slowest after each pass, and
// the tiles moved to even them out.
void print_balance(const PathOutcome& run, int processes);

// render_options.cpp: the options' specs and help, and the request they make (an error names
// the option and what was wrong with its value).
const std::vector<OptionSpec>& render_specs();
const CommandHelp& render_help();
Result<RenderRequest> read_render_request(const std::vector<std::string>& args);

}  // namespace raylane::cli
